#include "common/math/power.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "common/math/float_bits.h"

namespace glint {
namespace {

// The float nearest to x^y, from long double (64-bit significand) powl: an
// independent reference (x87, no FMA variant) whose own error is far below
// half a float ulp.
float nearest(float x, float y) {
  return static_cast<float>(std::pow(static_cast<long double>(x), static_cast<long double>(y)));
}

// Inputs where glibc 2.36's FMA version of powf (chosen at run time on CPUs
// with FMA) answers one ulp off the nearest float, and its other version
// does not: with std::pow this test fails on such a CPU, and CTest runs it
// once more with the FMA version turned off (power_test ... .WithoutFma).
// The operands pass through volatiles: the compiler would otherwise work
// out a call with constant operands itself, correctly rounded.
TEST(Power, NearestWhereGlibcsFmaVersionIsNot) {
  const struct {
    float x, y, want;
  } kCases[] = {{0x1.b5d6ep-1f, 0x1.5afb9cp+7f, 0x1.c8e114p-40f}, {0x1.c75a44p-1f, 0x1.a8c54ep+7f, 0x1.0d4774p-36f}};
  for (const auto& c : kCases) {
    volatile float x = c.x;
    volatile float y = c.y;
    EXPECT_EQ(floatToBits(power(x, y)), floatToBits(c.want)) << std::hexfloat << c.x << " " << c.y;
    EXPECT_EQ(nearest(x, y), c.want);
  }
}

// The renderer's uses: specular (V . R)^h with V . R in (0, 1] and any
// shininess, the sRGB curve's x^(1/2.4) for x in (0.0031308, 1].
TEST(Power, IsTheNearestFloatOverTheRenderersRanges) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_real_distribution<float> shininess(0.0f, 1000.0f);
  for (int i = 0; i < 300000; ++i) {
    const float x = std::max(unit(rng), 1e-6f);
    const float y = i % 4 == 0 ? 1.0f / 2.4f : shininess(rng);
    ASSERT_EQ(floatToBits(power(x, y)), floatToBits(nearest(x, y))) << std::hexfloat << x << " " << y;
  }
}

// Far from those ranges: subnormal and huge bases, results that underflow
// into the subnormals or overflow, negative exponents. At most one ulp off
// there (the subnormal results round once, in the final conversion).
TEST(Power, WithinAnUlpEverywhere) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> exponent(-149.0f, 127.0f);
  std::uniform_real_distribution<float> y(-40.0f, 40.0f);
  int exact = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const float x = std::exp2(exponent(rng));
    const float yy = y(rng);
    const float got = power(x, yy);
    const float want = nearest(x, yy);
    if (std::isinf(want) || want == 0.0f) {
      EXPECT_EQ(got, want) << std::hexfloat << x << " " << yy;
      ++exact;
      continue;
    }
    const auto a = static_cast<std::int64_t>(floatToBits(got));
    const auto b = static_cast<std::int64_t>(floatToBits(want));
    ASSERT_LE(std::abs(a - b), 1) << std::hexfloat << x << " " << yy << " " << got << " " << want;
    exact += a == b ? 1 : 0;
  }
  EXPECT_GT(exact, n - n / 10000);  // nearly always the nearest float
}

TEST(Power, ExactCases) {
  for (float x : {0x1p-149f, 1e-30f, 0.1f, 0.5f, 0.7f, 1.0f, 3.0f, 1e30f}) {
    EXPECT_EQ(power(x, 0.0f), 1.0f) << x;
    EXPECT_EQ(power(x, 1.0f), x) << x;
    EXPECT_EQ(power(x, 2.0f), nearest(x, 2.0f)) << x;
  }
  EXPECT_EQ(power(1.0f, 1e30f), 1.0f);
  EXPECT_EQ(power(0.25f, 0.5f), 0.5f);
  EXPECT_EQ(power(2.0f, 10.0f), 1024.0f);
  EXPECT_EQ(power(2.0f, -149.0f), 0x1p-149f);
  EXPECT_EQ(power(2.0f, 128.0f), std::numeric_limits<float>::infinity());
  EXPECT_EQ(power(0.5f, 151.0f), 0.0f);
}

// Zero, negative, infinite and NaN operands: std::pow's special values.
// e^x: the gaussian filter's arguments, -2 x^2 for |x| <= 1.5, and the
// whole range where e^x is a normal float.
TEST(Power, ExponentialIsTheNearestFloat) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> gaussian(-4.5f, 0.0f);
  std::uniform_real_distribution<float> wide(-87.0f, 88.0f);
  for (int i = 0; i < 300000; ++i) {
    const float x = i % 2 == 0 ? gaussian(rng) : wide(rng);
    const auto want = static_cast<float>(std::exp(static_cast<long double>(x)));
    ASSERT_EQ(floatToBits(exponential(x)), floatToBits(want)) << std::hexfloat << x;
  }
  EXPECT_EQ(exponential(0.0f), 1.0f);
  EXPECT_EQ(exponential(-std::numeric_limits<float>::infinity()), 0.0f);
  EXPECT_EQ(exponential(std::numeric_limits<float>::infinity()), std::numeric_limits<float>::infinity());
  EXPECT_EQ(exponential(1000.0f), std::numeric_limits<float>::infinity());
  EXPECT_EQ(exponential(-1000.0f), 0.0f);
  EXPECT_TRUE(std::isnan(exponential(std::numeric_limits<float>::quiet_NaN())));
}

// FLIP's L*a*b* takes cube roots of values in (0, 1.1]; across the floats'
// range too. The nearest float, from long double cbrtl, but within an ulp
// where the root lies within 2^-40 of a midpoint.
TEST(Power, CubeRootIsTheNearestFloat) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.0f, 1.1f);
  std::uniform_real_distribution<float> exponent(-149.0f, 127.0f);
  int exact = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const float x = i % 2 == 0 ? std::max(unit(rng), 1e-30f) : std::exp2(exponent(rng));
    const float want = static_cast<float>(std::cbrt(static_cast<long double>(x)));
    const std::int64_t ulps = static_cast<std::int64_t>(floatToBits(cubeRoot(x))) - floatToBits(want);
    ASSERT_LE(std::abs(ulps), 1) << std::hexfloat << x;
    exact += ulps == 0 ? 1 : 0;
  }
  EXPECT_EQ(exact, n);
  EXPECT_EQ(cubeRoot(0.0f), 0.0f);
  EXPECT_EQ(cubeRoot(8.0f), 2.0f);
  EXPECT_EQ(cubeRoot(-8.0f), -2.0f);
  EXPECT_TRUE(std::isinf(cubeRoot(std::numeric_limits<float>::infinity())));
}

TEST(Power, SpecialValuesAreStdPows) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (float x : {0.0f, -0.0f, -2.0f, -0.5f, inf, -inf, nan, 0.5f}) {
    for (float y : {0.0f, 1.0f, 2.0f, 0.5f, -1.0f, -3.0f, inf, -inf, nan}) {
      if (x > 0.0f && std::isfinite(x) && std::isfinite(y)) continue;
      const float want = std::pow(x, y);
      const float got = power(x, y);
      if (std::isnan(want)) {
        EXPECT_TRUE(std::isnan(got)) << x << " " << y;
      } else {
        EXPECT_EQ(floatToBits(got), floatToBits(want)) << x << " " << y;
      }
    }
  }
}

}  // namespace
}  // namespace glint
