#include "common/math/power.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "common/math/float_bits.h"
#include "common/math/polynomial.h"

namespace glint {
namespace {

constexpr double kLn2 = 0x1.62e42fefa39efp-1;
constexpr double kLog2e = 0x1.71547652b82fep0;
// log2: the mantissa's cell of width 1/128 in [1, 2), then ln(1 + r) for
// r < 1/128. exp2: 2^(j/64), then 2^f for |f| <= 1/128.
constexpr int kLogCells = 128;
constexpr int kExpSteps = 64;

// sum c[k] x^k for N = 6 or 7 coefficients, in Estrin's order: pairs,
// then pairs of pairs, so that the steps of one call overlap (any fixed
// order gives the same bits everywhere).
template <std::size_t N>
double estrin(const std::array<double, N>& c, double x) {
  static_assert(N == 6 || N == 7, "two levels of pairs");
  const double x2 = x * x;
  const double x4 = x2 * x2;
  const double low = (c[0] + c[1] * x) + (c[2] + c[3] * x) * x2;
  double high = c[4] + c[5] * x;
  if constexpr (N == 7) high += c[6] * x2;
  return low + high * x4;
}

// The series' coefficients, computed by the compiler: ln(1 + r) / r =
// sum (-1)^k r^k / (k + 1), and e^g = sum g^k / k!.
template <std::size_t N>
constexpr std::array<double, N> log1pOverR() {
  std::array<double, N> c{};
  for (std::size_t k = 0; k < N; ++k) c[k] = (k % 2 == 0 ? 1.0 : -1.0) / static_cast<double>(k + 1);
  return c;
}
template <std::size_t N>
constexpr std::array<double, N> expTaylor() {
  std::array<double, N> c{};
  double term = 1.0;
  for (std::size_t k = 0; k < N; ++k) {
    c[k] = term;
    term /= static_cast<double>(k + 1);
  }
  return c;
}

// ln(1 + r) for 0 <= r < 1/128: its series to r^7 (the next term is below
// 2^-59 of the sum).
double log1pSmall(double r) {
  static constexpr auto kC = log1pOverR<7>();
  return estrin(kC, r) * r;
}

// e^g for |g| <= ln(2) / 128: its series to g^5 (the next term is below
// 2^-54 of the sum).
double expSmall(double g) {
  static constexpr auto kC = expTaylor<6>();
  return estrin(kC, g);
}

// ln(c) for c in [1, 2): 2 atanh((c - 1) / (c + 1)) by its series, to a
// term below 2^-60 of the sum. For the tables alone.
double lnSeries(double c) {
  const double s = (c - 1.0) / (c + 1.0);
  double sum = 0.0;
  double odd = s;  // s^k
  for (int k = 1; k < 80; k += 2) {
    sum += odd / k;
    odd *= s * s;
  }
  return 2.0 * sum;
}

// Made once from the series above, so the same on every machine: ln(c) and
// 1 / c for the cells' left ends c = 1 + i / 128, and 2^(j / 64).
struct Tables {
  std::array<double, kLogCells> lnCell;
  std::array<double, kLogCells> invCell;
  std::array<double, kExpSteps> exp2Step;
  Tables() {
    for (std::size_t i = 0; i < kLogCells; ++i) {
      const double c = 1.0 + static_cast<double>(i) / kLogCells;
      lnCell[i] = lnSeries(c);
      invCell[i] = 1.0 / c;
    }
    // e^g for g < ln(2) by its series to g^30 (the next term is below
    // 2^-110 of the sum).
    static constexpr auto kC = expTaylor<31>();
    for (std::size_t j = 0; j < kExpSteps; ++j) {
      exp2Step[j] = horner(kC, kLn2 * static_cast<double>(j) / kExpSteps);
    }
  }
};

const Tables& tables() {
  static const Tables t;
  return t;
}

// log2(x) for finite x > 0.
double log2Positive(float x, const Tables& t) {
  int bias = 0;
  if (x < 0x1p-126f) {  // subnormal: into the normal range (exact)
    x *= 0x1p23f;
    bias = 23;
  }
  const std::uint32_t bits = floatToBits(x);
  const int exponent = static_cast<int>(bits >> 23) - 127 - bias;
  const double m = bitsToFloat((bits & 0x7fffffu) | 0x3f800000u);  // in [1, 2)
  const std::uint32_t cell = (bits >> 16) & (kLogCells - 1);
  const double c = 1.0 + static_cast<double>(cell) / kLogCells;
  const double r = (m - c) * t.invCell[cell];  // m - c is exact
  return exponent + (t.lnCell[cell] + log1pSmall(r)) * kLog2e;
}

// 2^e rounded to float, for finite e.
float exp2ToFloat(double e, const Tables& t) {
  if (e >= 129.0) return kInfinity;  // beyond the largest float
  if (e <= -160.0) return 0.0f;      // below half the least subnormal
  // 2^e = 2^n 2^(j/64) 2^f, with k = 64 n + j the integer nearest to 64 e.
  // Rounded by adding and taking away 1.5 * 2^52, which leaves no bits
  // below the units: std::nearbyint's answer without its library call.
  constexpr double kRound = 0x1.8p52;
  const double k = (e * kExpSteps + kRound) - kRound;
  const double f = e - k / kExpSteps;
  const auto ki = static_cast<std::int64_t>(k);
  const std::int64_t j = ki & (kExpSteps - 1);
  const std::int64_t n = (ki - j) / kExpSteps;
  const double scale = std::bit_cast<double>(static_cast<std::uint64_t>(n + 1023) << 52);
  return static_cast<float>(t.exp2Step[static_cast<std::size_t>(j)] * expSmall(f * kLn2) * scale);
}

}  // namespace

float power(float x, float y) {
  if (!(x > 0.0f) || !std::isfinite(x) || !std::isfinite(y)) return std::pow(x, y);
  const Tables& t = tables();
  return exp2ToFloat(y * log2Positive(x, t), t);
}

float cubeRoot(float x) {
  if (!(x > 0.0f) || !std::isfinite(x)) return std::cbrt(x);
  const double d = x;
  // A third of the exponent's bits, re-biased: within 4 % of the root.
  double y = std::bit_cast<double>(std::bit_cast<std::uint64_t>(d) / 3 + 0x2A9F7893782DA1CEull);
  for (int i = 0; i < 3; ++i) {  // Halley's method: the error cubes each step
    const double y3 = y * y * y;
    y *= (y3 + 2.0 * d) / (2.0 * y3 + d);
  }
  return static_cast<float>(y);
}

float exponential(float x) {
  if (!std::isfinite(x)) return std::exp(x);
  return exp2ToFloat(x * kLog2e, tables());
}

float twoToThe(float x) { return static_cast<float>(std::exp2(static_cast<double>(x))); }

}  // namespace glint
