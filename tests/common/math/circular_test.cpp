#include "common/math/circular.h"

#include <cmath>
#include <limits>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "common/math/float_bits.h"
#include "common/scene/transform.h"

namespace glint {
namespace {

// The floats nearest to sin x and cos x, from long double (64-bit
// significand) sinl and cosl: an independent reference whose own error is
// far below half a float ulp.
SineCosine nearest(float x) {
  const auto lx = static_cast<long double>(x);
  return {static_cast<float>(std::sin(lx)), static_cast<float>(std::cos(lx))};
}

void expectNearest(float x) {
  const SineCosine got = sineCosine(x);
  const SineCosine want = nearest(x);
  ASSERT_EQ(floatToBits(got.sin), floatToBits(want.sin)) << std::hexfloat << x;
  ASSERT_EQ(floatToBits(got.cos), floatToBits(want.cos)) << std::hexfloat << x;
}

// Angles a scene gives in degrees (a transform's rotation, the crease angle
// of smooth normals), and radians over many turns.
TEST(Circular, IsTheNearestFloat) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> degrees(-720.0f, 720.0f);
  std::uniform_real_distribution<float> turns(-400.0f, 400.0f);
  for (int d = -720; d <= 720; ++d) expectNearest(glm::radians(static_cast<float>(d)));
  for (int i = 0; i < 300000; ++i) expectNearest(i % 2 == 0 ? glm::radians(degrees(rng)) : turns(rng));
}

// The floats nearest to multiples of pi / 2, where the reduction cancels
// most: the sine or the cosine there is tiny.
TEST(Circular, IsTheNearestFloatNearMultiplesOfHalfPi) {
  for (int k = -4096; k <= 4096; ++k) {
    const auto x = static_cast<float>(k * 1.5707963267948966);
    expectNearest(x);
    expectNearest(nextFloatUp(x));
    expectNearest(std::nextafter(x, -kInfinity));
  }
}

TEST(Circular, SignedZeroAndTheLibraryBeyondItsRange) {
  EXPECT_EQ(floatToBits(sineCosine(0.0f).sin), floatToBits(0.0f));
  EXPECT_EQ(floatToBits(sineCosine(-0.0f).sin), floatToBits(-0.0f));
  EXPECT_EQ(sineCosine(0.0f).cos, 1.0f);
  for (float x : {0x1p21f, -0x1p30f, 1e30f, kInfinity, -kInfinity, std::numeric_limits<float>::quiet_NaN()}) {
    const SineCosine got = sineCosine(x);
    if (std::isnan(std::sin(x))) {
      EXPECT_TRUE(std::isnan(got.sin) && std::isnan(got.cos)) << x;
    } else {
      EXPECT_EQ(got.sin, std::sin(x)) << x;
      EXPECT_EQ(got.cos, std::cos(x)) << x;
    }
  }
}

// A fraction of a turn: within 2^-23 of sinl and cosl of 2 pi u over the
// whole turn, exact at the quarter turns.
TEST(Circular, TurnIsWithinTwoToTheMinus23) {
  const long double twoPi = 6.283185307179586476925286766559L;
  float worst = 0.0f;
  for (int i = 0; i <= 1 << 20; ++i) {
    const float u = static_cast<float>(i) * 0x1p-20f;
    for (float v : {u, std::nextafter(u, 2.0f), std::nextafter(u, -1.0f)}) {
      if (v < 0.0f || v > 1.0f) continue;
      const SineCosine got = turn(v);
      const long double angle = twoPi * static_cast<long double>(v);
      worst = std::max({worst, static_cast<float>(std::abs(got.sin - std::sin(angle))),
                        static_cast<float>(std::abs(got.cos - std::cos(angle)))});
    }
  }
  EXPECT_LE(worst, 0x1p-23f);
  const float quarters[][3] = {{0.0f, 0.0f, 1.0f}, {0.25f, 1.0f, 0.0f}, {0.5f, 0.0f, -1.0f}, {0.75f, -1.0f, 0.0f},
                               {1.0f, 0.0f, 1.0f}};
  for (const auto& q : quarters) {
    EXPECT_EQ(turn(q[0]).sin, q[1]) << q[0];  // -0 equals 0
    EXPECT_EQ(turn(q[0]).cos, q[2]) << q[0];
  }
}

// Transform's rotation is glm::rotate's matrix, operation for operation:
// where std::sin and std::cos give sineCosine's bits, the two matrices are
// the same bits.
TEST(Circular, TransformRotatesAsGlm) {
  int compared = 0;
  for (float degrees : {20.0f, 37.5f, 90.0f, -45.0f, 133.0f, 300.0f}) {
    const float angle = glm::radians(degrees);
    const SineCosine sc = sineCosine(angle);
    if (sc.sin != std::sin(angle) || sc.cos != std::cos(angle)) continue;
    Transform t;
    t.axis = {0.3f, 1.0f, -0.2f};
    t.angleDegrees = degrees;
    t.translate = {1.0f, 2.0f, 3.0f};
    const glm::mat4 want =
        glm::rotate(glm::translate(glm::mat4(1.0f), t.translate), angle, glm::normalize(t.axis));
    EXPECT_EQ(t.matrix(), want) << degrees;
    ++compared;
  }
  EXPECT_GE(compared, 4);
}

}  // namespace
}  // namespace glint
