// Sphere lights in the tracer: the soft shadow of a ball on a floor against
// the share of the light each floor point sees, worked out here in double
// precision over the cone the light's ball fills; unshadowed, a point light
// at the centre; the shadow rays a query takes; the same bytes however the
// frame is split.
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/render/linear_frame.h"
#include "common/render/sphere_light.h"
#include "tests/support/soft_shadow_check.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;

const glm::dvec3& kBall = test::kShadowBall;  // the occluder
constexpr double kBallRadius = test::kShadowBallRadius;
const glm::dvec3 kLight(1.5, 3.0, 0.0);
constexpr double kLightRadius = 0.6;

json lightJson(int samples) {
  return {{"type", "sphere"},
          {"position", {kLight.x, kLight.y, kLight.z}},
          {"radius", kLightRadius},
          {"samples", samples}};
}

// Where a ray from p along unit d enters a ball; infinity when it misses.
double entry(const glm::dvec3& p, const glm::dvec3& d, const glm::dvec3& centre, double radius) {
  const glm::dvec3 m = p - centre;
  const double b = glm::dot(m, d), c = glm::dot(m, m) - radius * radius;
  const double disc = b * b - c;
  if (disc < 0.0) return INFINITY;
  const double t = -b - std::sqrt(disc);
  return t > 0.0 ? t : INFINITY;
}

// Whether the cones from p to the light's ball and to the occluder are
// apart: p sees the whole light.
bool seesWhole(const glm::dvec3& p) {
  const glm::dvec3 toLight = kLight - p, toBall = kBall - p;
  const double apart = std::acos(glm::dot(toLight, toBall) / (glm::length(toLight) * glm::length(toBall)));
  return apart > std::asin(kLightRadius / glm::length(toLight)) + std::asin(kBallRadius / glm::length(toBall));
}

// The share of the light a floor point sees: 1 where the cones are apart,
// else a 200 x 200 midpoint grid over the cone to the light's ball, uniform
// in solid angle, each direction weighted by its cosine at the floor; a
// direction is shadowed when the occluder is met before the light's ball.
double visibleShare(const glm::dvec3& p) {
  if (seesWhole(p)) return 1.0;
  constexpr int kGrid = 200;
  const glm::dvec3 toLight = kLight - p;
  const double distance = glm::length(toLight);
  const glm::dvec3 w = toLight / distance;
  const glm::dvec3 t = glm::normalize(glm::cross(std::abs(w.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0), w));
  const glm::dvec3 b = glm::cross(w, t);
  const double cosMax = std::sqrt(1.0 - (kLightRadius / distance) * (kLightRadius / distance));
  double open = 0.0, total = 0.0;
  for (int i = 0; i < kGrid; ++i) {
    const double cosTheta = 1.0 - (i + 0.5) / kGrid * (1.0 - cosMax);
    const double sinTheta = std::sqrt(1.0 - cosTheta * cosTheta);
    for (int j = 0; j < kGrid; ++j) {
      const double phi = 2.0 * std::numbers::pi * (j + 0.5) / kGrid;
      const glm::dvec3 d = sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * b + cosTheta * w;
      total += d.y;
      if (!(entry(p, d, kBall, kBallRadius) < entry(p, d, kLight, kLightRadius))) open += d.y;
    }
  }
  return open / total;
}

TEST(SphereLight, SoftShadowFollowsTheShareOfTheBallSeen) {
  const Scene shadowed = test::sceneFromJson(test::floorScene(true, lightJson(400)).dump());
  const Scene open = test::sceneFromJson(test::floorScene(false, lightJson(400)).dump());
  RayStats stats;
  const LinearImage withBall = test::renderLinearFrame(shadowed, stats);
  const LinearImage without = test::renderLinearFrame(open, stats);
  test::expectShadowFollowsTheShareSeen(shadowed, withBall, without, visibleShare);
}

TEST(SphereLight, UnshadowedItIsAPointLightAtItsCentre) {
  // A diffuse floor and ball lit by a sphere light, and by a point light at
  // its centre: where nothing blocks the ball, the same bytes.
  const json ball = test::floorScene(true, lightJson(16));
  json point = ball;
  point["lights"][0] = {{"type", "point"}, {"position", {kLight.x, kLight.y, kLight.z}}};
  const FrameImage soft = test::render(test::sceneFromJson(ball.dump()), 2, 16).image;
  const FrameImage hard = test::render(test::sceneFromJson(point.dump()), 2, 16).image;
  const Scene scene = test::sceneFromJson(ball.dump());
  const Camera camera(scene.frame.camera, scene.frame.width, scene.frame.height);
  int lit = 0;
  for (int y = 0; y < scene.frame.height; ++y) {
    for (int x = 0; x < scene.frame.width; ++x) {
      const Ray ray = camera.generateRay({x + 0.5f, y + 0.5f});
      const glm::dvec3 o(ray.o), d(ray.d);
      if (glm::length(glm::cross(kBall - o, d)) < 1.05 * kBallRadius || !(d.y < 0.0)) continue;
      const glm::dvec3 p = o + (-o.y / d.y) * d;
      if (!seesWhole(p)) continue;
      ++lit;
      const std::size_t i = (static_cast<std::size_t>(y) * scene.frame.width + x) * 3;
      for (std::size_t c = 0; c < 3; ++c) ASSERT_EQ(soft.rgb[i + c], hard.rgb[i + c]) << x << ", " << y;
    }
  }
  EXPECT_GT(lit, 2000);
  EXPECT_NE(soft.rgb, hard.rgb);  // the shadows differ
}

TEST(SphereLight, FrameLightSamplesSetTheRaysPerShadowQuery) {
  test::expectFrameLightSamplesSetTheRays(lightJson(16));
}

TEST(SphereLight, SameBytesForAnyThreadsTilesAndPattern) { test::expectSameBytesHoweverSplit(lightJson(9)); }

// Balls far away, huge, tiny, or holding the whole scene: every pixel stays
// finite, and a scene point inside the ball is lit unshadowed.
TEST(SphereLight, HostileBallsStayFinite) {
  for (const auto& [position, radius] : std::vector<std::pair<glm::dvec3, double>>{
           {{1e30, 1e30, 1e30}, 1e29}, {{1e30, 1e30, 1e30}, 1e-30}, {{1.5, 3, 0}, 1e-30},
           {{1.5, 3, 0}, 3e38}, {{0, 1e-30, 0}, 1e-30}, {{-1e38, 1e38, 0}, 1e38}}) {
    json light = lightJson(4);
    light["position"] = {position.x, position.y, position.z};
    light["radius"] = radius;
    RayStats stats;
    const LinearImage image = test::renderLinearFrame(test::sceneFromJson(test::floorScene(true, light).dump()), stats);
    EXPECT_EQ(stats.nonFiniteSamples, 0u) << light;
    for (float v : image.rgb) ASSERT_TRUE(std::isfinite(v)) << light;
  }
}

TEST(SphereLight, RaysEndOnTheBallsNearSideWithinItsCone) {
  const glm::vec3 centre(0.3f, -2.0f, 5.0f);
  const glm::vec3 p(1.0f, 2.0f, -1.0f);
  constexpr float kRadius = 1.5f;
  const auto view = SphereLightView::from(centre, kRadius, p);
  ASSERT_TRUE(view);
  const double distance = glm::length(glm::dvec3(centre - p));
  const double cosMax = std::sqrt(1.0 - (kRadius / distance) * (kRadius / distance));
  for (int k = 0; k < 64; ++k) {
    for (const glm::vec2 u : {glm::vec2(0.0f), glm::vec2(0.5f), glm::vec2(0.999f)}) {
      const SphereLightView::Sample s = view->sample(jitteredStratum(64, k), u);
      const glm::dvec3 q = glm::dvec3(p) + static_cast<double>(s.distance) * glm::dvec3(s.direction);
      EXPECT_NEAR(glm::length(q - glm::dvec3(centre)), kRadius, 1e-4) << k;  // on the ball
      EXPECT_GE(glm::dot(glm::dvec3(s.direction), glm::dvec3(centre - p)) / distance, cosMax - 1e-6);
      EXPECT_GT(glm::dot(q - glm::dvec3(centre), glm::dvec3(p - centre)), 0.0);  // its near side
    }
  }
  EXPECT_FALSE(SphereLightView::from(centre, kRadius, centre + glm::vec3(1.0f, 0.0f, 0.0f)));  // in the ball
  EXPECT_FALSE(SphereLightView::from(glm::vec3(INFINITY), kRadius, p));
}

}  // namespace
}  // namespace glint
