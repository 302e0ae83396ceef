#include "common/math/float_bits.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(FloatBits, NextFloatUpIsNextafterTowardInfinity) {
  const float special[] = {0.0f,
                           -0.0f,
                           std::numeric_limits<float>::denorm_min(),
                           -std::numeric_limits<float>::denorm_min(),
                           std::numeric_limits<float>::min(),
                           -std::numeric_limits<float>::min(),
                           1.0f,
                           -1.0f,
                           kOneMinusEpsilon,
                           std::numeric_limits<float>::max(),
                           -std::numeric_limits<float>::max(),
                           kInfinity,
                           -kInfinity};
  for (float x : special) {
    EXPECT_EQ(floatToBits(nextFloatUp(x)), floatToBits(std::nextafter(x, kInfinity))) << x;
  }
  EXPECT_TRUE(std::isnan(nextFloatUp(std::numeric_limits<float>::quiet_NaN())));
  // Random bit patterns: every finite float and both infinities.
  std::mt19937 rng(7);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    const float x = bitsToFloat(static_cast<std::uint32_t>(rng()));
    if (std::isnan(x)) continue;
    ASSERT_EQ(floatToBits(nextFloatUp(x)), floatToBits(std::nextafter(x, kInfinity))) << x;
    ++checked;
  }
  EXPECT_GT(checked, 190000);
}

}  // namespace
}  // namespace glint
