#include "common/render/emitter_patches.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/test_support.h"

namespace glint {
namespace {

using json = nlohmann::json;

// A square emitter of side `side` and radiance 1, facing down at height
// `height` over the origin, and `extra` more emitting triangles far off.
Scene emitterScene(double side, double height, int extra = 0) {
  const double h = side / 2;
  json objects = json::array(
      {{{"type", "quad"},
        {"corners", {{-h, height, -h}, {h, height, -h}, {h, height, h}, {-h, height, h}}},
        {"material", "light"}}});
  for (int i = 0; i < extra; ++i) {
    objects.push_back({{"type", "triangle"},
                       {"vertices", {{100.0 + i, 0, 0}, {101.0 + i, 0, 0}, {100.0 + i, 1, 0}}},
                       {"material", "light"}});
  }
  const json scene = {{"glint", 1},
                      {"image", {{"width", 8}, {"height", 8}}},
                      {"camera", {{"eye", {0, 1, 5}}, {"look_at", {0, 0, 0}}, {"fov_y", 40}}},
                      {"tracing", {{"transport", "path"}}},
                      {"materials", {{"light", {{"color", {1, 1, 1}}, {"emission", {1, 1, 1}}}}}},
                      {"objects", objects}};
  return test::sceneFromJson(scene.dump());
}

// The irradiance under the corner of a w x l rectangle of radiance 1 at
// height h, parallel to the receiver: pi x the form factor of the two.
double cornerIrradiance(double w, double l, double h) {
  const double x = w / h, y = l / h;
  const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return 0.5 * (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy));
}

double unshadowed(const EmitterPatches& e, const glm::vec3& p, const glm::vec3& n) {
  glm::vec3 sum(0.0f);
  for (const EmitterPatches::Patch& patch : e.patches()) sum += patch.irradianceAt(p, n);
  return sum.x;
}

// The same by brute force: radiance 1 x |cos_e| cos / d^2 over a grid of
// `cells` x `cells` points on each triangle (the unit square's map), where
// the receiver faces them, in double.
double summed(const EmitterPatches& e, const glm::dvec3& p, const glm::dvec3& n, int cells) {
  double sum = 0.0;
  for (const EmitterPatches::Patch& patch : e.patches()) {
    const double area = 0.5 * glm::length(glm::cross(glm::dvec3(patch.edge1), glm::dvec3(patch.edge2)));
    for (int i = 0; i < cells; ++i) {
      for (int j = 0; j < cells; ++j) {
        const double s = (i + 0.5) / cells, t = (j + 0.5) / cells, r = std::sqrt(s);
        const glm::dvec3 q = glm::dvec3(patch.corner) + r * (1 - t) * glm::dvec3(patch.edge1) +
                             r * t * glm::dvec3(patch.edge2);
        const glm::dvec3 to = q - p;
        const double d2 = glm::dot(to, to), cosine = glm::dot(to, n) / std::sqrt(d2);
        if (cosine <= 0) continue;
        const double cosE = std::abs(glm::dot(to, glm::dvec3(patch.normal))) / std::sqrt(d2);
        sum += cosE * cosine / d2 * area / (double(cells) * cells);
      }
    }
  }
  return sum;
}

// Under the middle of the square, the triangles' closed form is the
// square's (four corners' rectangles), from above as from below; a
// receiver turned away gets nothing; one the square straddles the horizon
// of gets the part in front of it, and one in the square's plane nothing.
TEST(EmitterPatches, TheirClosedFormIsTheSquaresIrradiance) {
  const Scene scene = emitterScene(0.5, 2.0);
  const std::optional<EmitterPatches> e = EmitterPatches::of(scene, EffectPlan::derive(scene), 64);
  ASSERT_TRUE(e);
  ASSERT_EQ(e->patches().size(), 2u);
  EXPECT_EQ(e->points(), 64);
  const double exact = 4 * cornerIrradiance(0.25, 0.25, 2.0);
  EXPECT_NEAR(unshadowed(*e, glm::vec3(0.0f), glm::vec3(0, 1, 0)), exact, 1e-5 * exact);
  EXPECT_NEAR(unshadowed(*e, glm::vec3(0, 4, 0), glm::vec3(0, -1, 0)), exact, 1e-5 * exact);
  EXPECT_EQ(unshadowed(*e, glm::vec3(0.0f), glm::vec3(0, -1, 0)), 0.0);
  // Two corners' rectangles of 0.5 x 0.25: the square's half beyond x = 0.
  const double half = 2 * cornerIrradiance(0.5, 0.25, 2.0);
  EXPECT_NEAR(unshadowed(*e, glm::vec3(-0.25f, 0, 0), glm::vec3(0, 1, 0)), half, 1e-5 * half);
  EXPECT_EQ(unshadowed(*e, glm::vec3(1, 2, 0), glm::vec3(0, 1, 0)), 0.0);
  for (const glm::vec3 n : {glm::vec3(1, 0, 0), glm::normalize(glm::vec3(1, 1, 0)), glm::normalize(glm::vec3(0.3, -1, 1))}) {
    const glm::vec3 p(0.1f, 1.9f, 0.05f);  // the square's horizon cuts it for each n
    const double brute = summed(*e, p, n, 1500);
    EXPECT_NEAR(unshadowed(*e, p, n), brute, 2e-3 * brute) << n.x << " " << n.y << " " << n.z;
  }
}

// The default: kDefaultPoints shared by area; a point drawn in the unit
// square lands on the triangle.
TEST(EmitterPatches, PointsAreSharedByAreaAndLieOnTheTriangle) {
  const Scene scene = emitterScene(0.5, 2.0);
  const std::optional<EmitterPatches> e = EmitterPatches::of(scene, EffectPlan::derive(scene), 0);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->points(), EmitterPatches::kDefaultPoints);
  for (const EmitterPatches::Patch& patch : e->patches()) {
    for (const Stratum& s : patch.strata) EXPECT_NEAR(patch.at({s.x1, s.y1}).y, 2.0f, 1e-6f);
    const glm::vec3 corner = patch.at({0.999f, 0.999f});
    EXPECT_NEAR(glm::length(corner - (patch.corner + patch.edge2)), 0.0f, 0.01f);
  }
}

// More emitting triangles than kMaxPatches: none (the tracer draws points
// at random, the raster cannot draw their light).
TEST(EmitterPatches, ManyEmittersAreNotPatches) {
  const Scene few = emitterScene(0.5, 2.0, EmitterPatches::kMaxPatches - 2);
  const Scene many = emitterScene(0.5, 2.0, EmitterPatches::kMaxPatches - 1);
  EXPECT_TRUE(EmitterPatches::of(few, EffectPlan::derive(few), 0));
  EXPECT_FALSE(EmitterPatches::of(many, EffectPlan::derive(many), 0));
}

}  // namespace
}  // namespace glint
