#pragma once

#include <cmath>
#include <cstdio>
#include <functional>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/image/linear_image.h"
#include "common/scene/camera.h"
#include "common/scene/scene.h"

namespace glint::test {

// A soft shadow cast by a ball on the floor (the plane y = 0) held to the
// share of the light each floor point sees, worked out by the test: for
// every pixel of the floor clear of the ball's silhouette, the shadowed
// frame's green over the unshadowed one's is `share(p)` within the sampling
// noise; where the whole light is seen, it is 1 to the bit (the ratio
// estimator), where none is, 0. The frames have enough of each kind.
inline void expectShadowFollowsTheShareSeen(const Scene& scene, const LinearImage& shadowed, const LinearImage& open,
                                            const glm::dvec3& ball, double radius,
                                            const std::function<double(const glm::dvec3&)>& share) {
  const Camera camera(scene.frame.camera, scene.frame.width, scene.frame.height);
  int penumbra = 0, umbra = 0, lit = 0, litExact = 0;
  double errorSum = 0.0, worst = 0.0;
  for (int y = 0; y < shadowed.height; ++y) {
    for (int x = 0; x < shadowed.width; ++x) {
      const Ray ray = camera.generateRay({x + 0.5f, y + 0.5f});
      const glm::dvec3 o(ray.o), d(ray.d);
      // The ball and its silhouette's pixels aside.
      if (glm::length(glm::cross(ball - o, d)) < 1.05 * radius || !(d.y < 0.0)) continue;
      const glm::dvec3 p = o + (-o.y / d.y) * d;
      const std::size_t i = (static_cast<std::size_t>(y) * shadowed.width + x) * 3 + 1;
      if (!(open.rgb[i] > 0.0f)) continue;
      const double ratio = shadowed.rgb[i] / open.rgb[i];
      const double expected = share(p);
      if (expected == 1.0) {
        ++lit;
        litExact += ratio == 1.0 ? 1 : 0;
        continue;
      }
      if (expected == 0.0) {
        ++umbra;
        EXPECT_EQ(ratio, 0.0) << "umbra pixel " << x << ", " << y;
        continue;
      }
      ++penumbra;
      errorSum += std::abs(ratio - expected);
      worst = std::max(worst, std::abs(ratio - expected));
      EXPECT_NEAR(ratio, expected, 0.04) << "pixel " << x << ", " << y;
    }
  }
  EXPECT_GT(penumbra, 300);
  EXPECT_GT(umbra, 20);
  EXPECT_GT(lit, 2000);
  // A jittered point may still graze the ball at the penumbra's outer edge.
  EXPECT_GE(litExact, lit * 98 / 100);
  EXPECT_LT(errorSum / penumbra, 0.006) << "worst " << worst;
  std::printf("penumbra %d umbra %d lit %d (exact %d) mean error %.5f worst %.4f\n", penumbra, umbra, lit, litExact,
              errorSum / penumbra, worst);
}

}  // namespace glint::test
