// Area lights in the tracer: the soft shadow of a sphere on a floor against
// the share of the light each floor point sees, computed here in double
// precision; the frame's light_samples; the same bytes however it is split.
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/base/thread_pool.h"
#include "common/render/linear_frame.h"
#include "common/render/prepared_scene.h"
#include "tests/support/soft_shadow_check.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;

const glm::dvec3& kSphere = test::kShadowBall;
constexpr double kRadius = test::kShadowBallRadius;
const glm::dvec3 kLight(1.5, 3.0, 0.0);
const glm::dvec3 kU(1.5, 0.0, 0.0);
const glm::dvec3 kV(0.0, 0.0, 1.5);  // u x v points down, at the floor

json lightJson(int samples) {
  return {{"type", "area"},
          {"position", {kLight.x, kLight.y, kLight.z}},
          {"u", {kU.x, kU.y, kU.z}},
          {"v", {kV.x, kV.y, kV.z}},
          {"samples", samples}};
}

json floorScene(bool sphere, int lightSamples) { return test::floorScene(sphere, lightJson(lightSamples)); }

bool segmentHitsSphere(const glm::dvec3& p, const glm::dvec3& q) {
  const glm::dvec3 d = q - p;
  const glm::dvec3 m = p - kSphere;
  const double a = glm::dot(d, d), b = glm::dot(m, d), c = glm::dot(m, m) - kRadius * kRadius;
  const double disc = b * b - a * c;
  if (disc < 0.0) return false;
  const double t = (-b - std::sqrt(disc)) / a;
  return t > 0.0 && t < 1.0;
}

// The share of the light a floor point sees, each point of the light weighted
// by the light it gives the floor (the cosine at p; no attenuation): a
// 200 x 200 midpoint grid over the parallelogram.
double visibleShare(const glm::dvec3& p) {
  constexpr int kGrid = 200;
  const glm::dvec3 corner = kLight - 0.5 * kU - 0.5 * kV;
  double open = 0.0, total = 0.0;
  for (int i = 0; i < kGrid; ++i) {
    for (int j = 0; j < kGrid; ++j) {
      const glm::dvec3 q = corner + (i + 0.5) / kGrid * kU + (j + 0.5) / kGrid * kV;
      const double w = (q.y - p.y) / glm::length(q - p);
      total += w;
      if (!segmentHitsSphere(p, q)) open += w;
    }
  }
  return open / total;
}

TEST(AreaLight, SoftShadowFollowsTheShareOfTheLightSeen) {
  const Scene shadowed = test::sceneFromJson(floorScene(true, 400).dump());
  const Scene open = test::sceneFromJson(floorScene(false, 400).dump());
  RayStats stats;
  const LinearImage withSphere = test::renderLinearFrame(shadowed, stats);
  const LinearImage without = test::renderLinearFrame(open, stats);
  test::expectShadowFollowsTheShareSeen(shadowed, withSphere, without, visibleShare);
}

TEST(AreaLight, FrameLightSamplesSetThePointsPerShadowQuery) {
  test::expectFrameLightSamplesSetTheRays(lightJson(16));
}

TEST(AreaLight, SameBytesForAnyThreadsTilesAndPattern) { test::expectSameBytesHoweverSplit(lightJson(9)); }

TEST(AreaLight, PointLightsTakeNoSampleOfTheLight) {
  // The same scene with a point light at the area light's centre: each lit
  // floor point casts one shadow ray, as it always did.
  json j = floorScene(true, 16);
  j["lights"][0] = {{"type", "point"}, {"position", {kLight.x, kLight.y, kLight.z}}};
  const Scene scene = test::sceneFromJson(j.dump());
  RayStats stats;
  test::renderLinearFrame(scene, stats);
  EXPECT_LE(stats.shadow, stats.primary);
}

}  // namespace
}  // namespace glint
