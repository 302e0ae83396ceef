// Spot and directional lights in the tracer: a floor lit by each, every
// pixel against the light's definition computed here in double precision
// (the cone's falloff, Lambert's cosine, the shadow of a sphere along
// parallel rays); the same bytes however the frame is split.
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/base/thread_pool.h"
#include "common/render/linear_frame.h"
#include "common/render/prepared_scene.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;

const glm::dvec3 kSphere(0.5, 1.0, -0.5);
constexpr double kRadius = 0.5;
const glm::dvec3 kSpotAt(-1.0, 3.0, 0.5);
const glm::dvec3 kSpotAxis = glm::normalize(glm::dvec3(0.3, -1.0, -0.2));
const glm::dvec3 kSunTravel = glm::normalize(glm::dvec3(-0.9, -1.0, 1.2));
constexpr double kInnerDegrees = 25.0, kOuterDegrees = 40.0;

json floorScene(const json& light, bool sphere) {
  json objects = json::array({{{"type", "quad"},
                               {"corners", {{-8, 0, -8}, {8, 0, -8}, {8, 0, 8}, {-8, 0, 8}}},
                               {"material", "white"}}});
  if (sphere) {
    objects.push_back({{"type", "sphere"}, {"center", {kSphere.x, kSphere.y, kSphere.z}}, {"radius", kRadius},
                       {"material", "white"}});
  }
  return {{"glint", 1},
          {"image", {{"width", 96}, {"height", 72}}},
          {"camera", {{"eye", {0, 6, 5}}, {"look_at", {0, 0, 0}}, {"fov_y", 55}}},
          {"materials", {{"white", {{"color", {1, 1, 1}}, {"diffuse", 1}}}}},
          {"lights", {light}},
          {"objects", objects}};
}

json spotLight() {
  return {{"type", "spot"},
          {"position", {kSpotAt.x, kSpotAt.y, kSpotAt.z}},
          {"direction", {kSpotAxis.x, kSpotAxis.y, kSpotAxis.z}},
          {"inner_angle", kInnerDegrees},
          {"outer_angle", kOuterDegrees},
          {"attenuation", {1, 0, 0.05}}};
}

json sunLight() { return {{"type", "directional"}, {"direction", {kSunTravel.x, kSunTravel.y, kSunTravel.z}}}; }

bool rayHitsSphere(const glm::dvec3& p, const glm::dvec3& d) {
  const glm::dvec3 m = p - kSphere;
  const double b = glm::dot(m, d), c = glm::dot(m, m) - kRadius * kRadius;
  return b * b - c >= 0.0 && -b - std::sqrt(b * b - c) > 0.0;
}

// Each floor pixel's centre (the sphere's pixels and those `expected` has no
// value for left out) against `expected`.
template <typename Expected>
void expectFloor(const Scene& scene, const LinearImage& image, Expected expected, int& compared, double& worst) {
  const Camera camera(scene.frame.camera, scene.frame.width, scene.frame.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const Ray ray = camera.generateRay({x + 0.5f, y + 0.5f});
      const glm::dvec3 o(ray.o), d(ray.d);
      if (!(d.y < 0.0) || glm::length(glm::cross(kSphere - o, d)) < 1.05 * kRadius) continue;
      const glm::dvec3 p = o + (-o.y / d.y) * d;
      if (std::max(std::abs(p.x), std::abs(p.z)) > 7.9) continue;  // past the floor's edge
      const std::optional<double> want = expected(p);
      if (!want) continue;
      const double got = image.rgb[(static_cast<std::size_t>(y) * image.width + x) * 3 + 1];
      worst = std::max(worst, std::abs(got - *want));
      EXPECT_NEAR(got, *want, 1e-5 + 1e-5 * *want) << "pixel " << x << ", " << y;
      ++compared;
    }
  }
}

TEST(SpotLight, FloorFollowsTheConesFalloff) {
  const Scene scene = test::sceneFromJson(floorScene(spotLight(), false).dump());
  const LinearImage image = test::renderLinearFrame(scene);
  const double cosInner = std::cos(kInnerDegrees * M_PI / 180.0), cosOuter = std::cos(kOuterDegrees * M_PI / 180.0);
  int compared = 0, inner = 0, dark = 0;
  double worst = 0.0;
  expectFloor(scene, image, [&](const glm::dvec3& p) -> std::optional<double> {
    const double dist = glm::length(kSpotAt - p);
    const glm::dvec3 l = (kSpotAt - p) / dist;
    const double c = -glm::dot(kSpotAxis, l);
    const double t = std::clamp((c - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
    inner += t == 1.0 ? 1 : 0;
    dark += t == 0.0 ? 1 : 0;
    return t * t * l.y / (1.0 + 0.05 * dist * dist);
  }, compared, worst);
  EXPECT_GT(inner, 300);
  EXPECT_GT(dark, 1000);
  EXPECT_GT(compared - inner - dark, 300);  // the ramp between the cones
  std::printf("spot: %d pixels (%d inside the inner cone, %d outside the outer), worst %.2e\n", compared, inner, dark,
              worst);
}

TEST(DirectionalLight, FloorIsLambertsCosineAndTheSphereShadowsAlongTheLight) {
  const Scene scene = test::sceneFromJson(floorScene(sunLight(), true).dump());
  const LinearImage image = test::renderLinearFrame(scene);
  const double cosine = -kSunTravel.y;
  int compared = 0, shadowed = 0;
  double worst = 0.0;
  expectFloor(scene, image, [&](const glm::dvec3& p) -> std::optional<double> {
    // Points whose ray to the light grazes the sphere are left out.
    const glm::dvec3 toSun = -kSunTravel;
    const double miss = glm::length(glm::cross(kSphere - p, toSun));
    if (std::abs(miss - kRadius) < 0.02) return std::nullopt;
    const bool blocked = rayHitsSphere(p, toSun);
    shadowed += blocked ? 1 : 0;
    return blocked ? 0.0 : cosine;
  }, compared, worst);
  EXPECT_GT(shadowed, 60);
  EXPECT_GT(compared - shadowed, 3000);
  std::printf("directional: %d pixels, %d in the shadow, worst %.2e\n", compared, shadowed, worst);
}

TEST(SpotAndDirectionalLights, SameBytesForAnyThreadsAndTiles) {
  json j = floorScene(spotLight(), true);
  j["lights"].push_back(sunLight());
  j["sampling"] = {{"pattern", "jittered"}, {"samples", 4}};
  const Scene scene = test::sceneFromJson(j.dump());
  EXPECT_EQ(test::render(scene, 1, 64).image.rgb, test::render(scene, 2, 7).image.rgb);
}

}  // namespace
}  // namespace glint
