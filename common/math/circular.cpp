#include "common/math/circular.h"

#include <array>
#include <cmath>
#include <cstdint>

#include "common/math/polynomial.h"

namespace glint {
namespace {

// pi / 2 in three parts (Cody and Waite 1980): the first two of 29
// significant bits, so that their products with a quadrant count below
// 2^21 are exact; the third the rest, rounded.
constexpr double kHalfPi1 = 0x1.921fb54p0;
constexpr double kHalfPi2 = 0x1.10b4611p-30;
constexpr double kHalfPi3 = 0x1.4c4c6628b80dcp-59;
constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;

// The series' coefficients, computed by the compiler: (-1)^k / (2k + 1)!
// for sin r / r and (-1)^k / (2k)! for cos r, as functions of r^2.
template <std::size_t N>
constexpr std::array<double, N> seriesOf(int first) {
  std::array<double, N> c{};
  double factorial = 1.0;
  for (int n = 1; n <= first; ++n) factorial *= n;
  for (std::size_t k = 0; k < N; ++k) {
    c[k] = (k % 2 == 0 ? 1.0 : -1.0) / factorial;
    const int n = first + 2 * static_cast<int>(k);
    factorial *= (n + 1.0) * (n + 2.0);
  }
  return c;
}

// For |r| <= pi / 4 (and a little more): to r^17 and r^18, the next terms
// below 2^-60 of the sums.
constexpr auto kSin = seriesOf<9>(1);
constexpr auto kCos = seriesOf<10>(0);

// sin and cos of k pi/2 + r from s = sin r and c = cos r (negation is
// exact, so negating before or after the rounding to float is the same).
SineCosine turnedBy(int quarter, float s, float c) {
  switch (quarter) {
    case 0:
      return {s, c};
    case 1:
      return {c, -s};
    case 2:
      return {-s, -c};
    default:
      return {-c, s};
  }
}

}  // namespace

SineCosine sineCosine(float x) {
  if (!(std::abs(x) <= 0x1p20f)) return {std::sin(x), std::cos(x)};
  // x = k pi/2 + r with k the integer nearest to x 2/pi (rounded by adding
  // and taking away 1.5 * 2^52, which leaves no bits below the units).
  constexpr double kRound = 0x1.8p52;
  const double k = (static_cast<double>(x) * kTwoOverPi + kRound) - kRound;
  const double r = ((x - k * kHalfPi1) - k * kHalfPi2) - k * kHalfPi3;
  const double r2 = r * r;
  const double s = r * horner(kSin, r2);
  const double c = horner(kCos, r2);
  return turnedBy(static_cast<int>(static_cast<std::int64_t>(k) & 3), static_cast<float>(s), static_cast<float>(c));
}

SineCosine turn(float u) {
  const float quarters = 4.0f * u;
  const float q = std::floor(quarters + 0.5f);
  // Exact (Sterbenz): quarters and q are within a factor of two of each other.
  const float a = (quarters - q) * 1.57079632679489662f;  // |a| <= pi/4 and a little
  const float a2 = a * a;
  const float s = a * (1.0f + a2 * (-1.0f / 6.0f + a2 * (1.0f / 120.0f + a2 * (-1.0f / 5040.0f + a2 / 362880.0f))));
  const float c =
      1.0f + a2 * (-0.5f + a2 * (1.0f / 24.0f + a2 * (-1.0f / 720.0f + a2 * (1.0f / 40320.0f - a2 / 3628800.0f))));
  return turnedBy(static_cast<int>(q) & 3, s, c);
}

}  // namespace glint
