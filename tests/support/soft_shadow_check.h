#pragma once

#include <cmath>
#include <cstdio>
#include <functional>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/base/enum_words.h"
#include "common/image/linear_image.h"
#include "common/scene/camera.h"
#include "common/scene/scene.h"
#include "tests/support/test_support.h"

namespace glint::test {

// The ball that casts the shadow, on a white diffuse floor of 16 x 16.
inline const glm::dvec3 kShadowBall(0.0, 1.0, 0.0);
constexpr double kShadowBallRadius = 0.5;

// A 96 x 72 frame of the floor under `light`, the ball on it or not.
inline nlohmann::json floorScene(bool ball, const nlohmann::json& light) {
  nlohmann::json objects = nlohmann::json::array({{{"type", "quad"},
                                                   {"corners", {{-8, 0, -8}, {8, 0, -8}, {8, 0, 8}, {-8, 0, 8}}},
                                                   {"material", "white"}}});
  if (ball) {
    objects.push_back({{"type", "sphere"},
                       {"center", {kShadowBall.x, kShadowBall.y, kShadowBall.z}},
                       {"radius", kShadowBallRadius},
                       {"material", "white"}});
  }
  return {{"glint", 1},
          {"image", {{"width", 96}, {"height", 72}}},
          {"camera", {{"eye", {0, 6, 4}}, {"look_at", {-0.6, 0, 0}}, {"fov_y", 50}}},
          {"materials", {{"white", {{"color", {1, 1, 1}}, {"diffuse", 1}}}}},
          {"lights", {light}},
          {"objects", objects}};
}

// The ball's soft shadow on the floor (the plane y = 0) held to the
// share of the light each floor point sees, worked out by the test: for
// every pixel of the floor clear of the ball's silhouette, the shadowed
// frame's green over the unshadowed one's is `share(p)` within the sampling
// noise; where the whole light is seen, it is 1 to the bit (the ratio
// estimator), where none is, 0. The frames have enough of each kind.
inline void expectShadowFollowsTheShareSeen(const Scene& scene, const LinearImage& shadowed, const LinearImage& open,
                                            const std::function<double(const glm::dvec3&)>& share) {
  const glm::dvec3& ball = kShadowBall;
  const double radius = kShadowBallRadius;
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

// The ball's shadow under a soft light of 16 samples, then of the frame's
// light_samples 4: a quarter of the shadow rays.
inline void expectFrameLightSamplesSetTheRays(const nlohmann::json& light) {
  nlohmann::json j = floorScene(true, light);
  j["lights"][0]["samples"] = 16;
  Scene scene = sceneFromJson(j.dump());
  RayStats own, four;
  renderLinearFrame(scene, own);
  scene.frame.sampling.lightSamples = 4;
  renderLinearFrame(scene, four);
  EXPECT_GT(four.shadow, 0u);
  EXPECT_EQ(own.primary, four.primary);
  EXPECT_NEAR(static_cast<double>(own.shadow) / static_cast<double>(four.shadow), 4.0, 0.05);
}

// The ball's shadow under a soft light: the same bytes on one thread in
// large tiles and on two in small ones, under every sample pattern.
inline void expectSameBytesHoweverSplit(const nlohmann::json& light) {
  Scene scene = sceneFromJson(floorScene(true, light).dump());
  for (SamplePattern pattern : {SamplePattern::kRegular, SamplePattern::kJittered, SamplePattern::kAdaptive,
                                SamplePattern::kPerceptual}) {
    scene.frame.sampling.pattern = pattern;
    scene.frame.sampling.samples = 4;
    const FrameImage one = render(scene, 1, 64).image;
    const FrameImage split = render(scene, 2, 7).image;
    EXPECT_EQ(one.rgb, split.rgb) << enumWord(pattern);
  }
}

}  // namespace glint::test
