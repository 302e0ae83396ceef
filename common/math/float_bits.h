#pragma once

#include <bit>
#include <cstdint>
#include <limits>

namespace glint {

// Rounding-error bound for n floating-point operations (pbrt-v4, section
// 6.8.1): gamma(n) = n u / (1 - n u), with u the unit roundoff (2^-24).
constexpr float gamma(int n) {
  constexpr float kUnitRoundoff = std::numeric_limits<float>::epsilon() * 0.5f;
  return (n * kUnitRoundoff) / (1.0f - n * kUnitRoundoff);
}

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// The largest float below 1: where a [0, 1) value may round up to 1.0.
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

inline std::uint32_t floatToBits(float f) { return std::bit_cast<std::uint32_t>(f); }
inline float bitsToFloat(std::uint32_t u) { return std::bit_cast<float>(u); }

// The next float above x, as std::nextafter(x, +inf) but inline (the library
// call was a few per cent of a frame): +inf and NaN stay, -0 and +0 give the
// smallest subnormal.
inline float nextFloatUp(float x) {
  if (x != x || x == std::numeric_limits<float>::infinity()) return x;
  if (x == 0.0f) return std::numeric_limits<float>::denorm_min();
  const std::uint32_t bits = floatToBits(x);
  return bitsToFloat(x > 0.0f ? bits + 1 : bits - 1);
}

}  // namespace glint
