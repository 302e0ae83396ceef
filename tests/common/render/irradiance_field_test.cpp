#include "common/render/irradiance_field.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/base/thread_pool.h"
#include "common/render/field_probes.h"
#include "common/render/linear_frame.h"
#include "common/render/renderer.h"
#include "common/scene/shading.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using json = nlohmann::json;
constexpr float kPi = 3.14159265f;

TEST(IrradianceField, TheOctahedralMapsTwoWaysAgree) {
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const glm::vec2 point((x + 0.5f) / 64.0f, (y + 0.5f) / 64.0f);
      const glm::vec3 d = octahedralDirection(point);
      ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
      const glm::vec2 back = glsl::octahedralPoint(d);
      ASSERT_NEAR(back.x, point.x, 1e-4f) << x << " " << y;
      ASSERT_NEAR(back.y, point.y, 1e-4f) << x << " " << y;
    }
  }
}

// Equal areas of the square are equal areas of the sphere: over a grid of
// the square, the mean of z is 0 and of z^2 one third, as over the sphere.
TEST(IrradianceField, TheOctahedralMapIsEqualArea) {
  double z = 0.0, z2 = 0.0, upperQuarter = 0.0;
  constexpr int kSide = 256;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const glm::vec3 d = octahedralDirection({(x + 0.5f) / kSide, (y + 0.5f) / kSide});
      z += d.z;
      z2 += d.z * d.z;
      upperQuarter += d.z > 0.5f ? 1.0 : 0.0;  // a cap of a quarter of the sphere
    }
  }
  constexpr double kCount = double(kSide) * kSide;
  EXPECT_NEAR(z / kCount, 0.0, 1e-4);
  EXPECT_NEAR(z2 / kCount, 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(upperQuarter / kCount, 0.25, 2e-3);
}

// A closed box of six quads, each emitting `emission` and reflecting
// `albedo` diffusely; path transport.
json emittingBox(double emission, double albedo) {
  json objects = json::array();
  const double s = 2.0;
  const std::vector<std::vector<std::vector<double>>> faces = {
      {{0, 0, 0}, {s, 0, 0}, {s, 0, s}, {0, 0, s}}, {{0, s, 0}, {0, s, s}, {s, s, s}, {s, s, 0}},
      {{0, 0, 0}, {0, 0, s}, {0, s, s}, {0, s, 0}}, {{s, 0, 0}, {s, s, 0}, {s, s, s}, {s, 0, s}},
      {{0, 0, 0}, {0, s, 0}, {s, s, 0}, {s, 0, 0}}, {{0, 0, s}, {s, 0, s}, {s, s, s}, {0, s, s}}};
  for (const auto& f : faces) objects.push_back({{"type", "quad"}, {"corners", f}, {"material", "wall"}});
  return {{"glint", 1},
          {"image", {{"width", 8}, {"height", 8}}},
          {"camera", {{"eye", {1, 1, 1.5}}, {"look_at", {1, 1, 0}}, {"up", {0, 1, 0}}, {"fov_y", 60}}},
          {"tracing", {{"transport", "path"}, {"max_bounces", 4}}},
          {"materials",
           {{"wall", {{"color", {1, 1, 1}}, {"diffuse", albedo}, {"emission", {emission, emission, emission}}}}}},
          {"objects", objects}};
}

IrradianceField fieldOf(const Scene& scene, const FieldSettings& settings) {
  const PreparedScene prepared(scene, BvhSettings{});
  RayStats stats;
  return buildField(prepared, scene.frame, settings, stats);
}

// Inside a closed box whose walls emit radiance 1 and reflect half of what
// arrives, the walls reflect 0.5 + 0.25 + 0.125 + 0.0625 (the bounces path
// transport takes: 4 at a surface, so 3 past a probe's ray's hit, each
// with its light sampled), evenly in every direction: the field's
// irradiance is pi times that toward every normal, everywhere (within the
// noise of each bounce's one sample of the walls' light). What the
// walls emit is not in it (the point it lights samples the emitters).
TEST(IrradianceField, InsideAnEmittingBoxTheFieldHoldsTheReflectedLightEverywhere) {
  const IrradianceField field = fieldOf(test::sceneFromJson(emittingBox(1.0, 0.5).dump()), {4, 4096});
  const float expected = kPi * (0.5f + 0.25f + 0.125f + 0.0625f);
  for (const glm::vec3 p : {glm::vec3(1.0f), glm::vec3(0.3f, 1.7f, 0.9f), glm::vec3(1.9f, 0.1f, 0.2f)}) {
    for (const glm::vec3 n : {glm::vec3(0, 1, 0), glm::vec3(0, 0, -1), glm::normalize(glm::vec3(1, -2, 3))}) {
      const IrradianceField::Lookup got = field.irradiance(p, n);
      EXPECT_TRUE(got.decided);
      EXPECT_NEAR(got.irradiance.x, expected, 0.03f * expected) << p.x << " " << n.x;
    }
  }
}

TEST(IrradianceField, ItHoldsNoEmission) {
  const IrradianceField field = fieldOf(test::sceneFromJson(emittingBox(1.0, 0.0).dump()), {4, 256});
  EXPECT_EQ(field.irradiance(glm::vec3(1.0f), {0, 1, 0}).irradiance, glm::vec3(0.0f));
}

// Above a wide floor of albedo 0.5 under a directional light of irradiance
// pi, the floor's radiance is 0.5: a surface facing it receives 0.5 pi, one
// facing away 0, one on its side 0.25 pi: the irradiance 0.5 pi (1 - n.y) /
// 2 is linear in n, which order 2 holds exactly.
TEST(IrradianceField, AboveALitFloorTheIrradianceFollowsTheNormal) {
  json scene = emittingBox(0.0, 0.5);
  const double w = 20.0;
  scene["objects"] = {
      {{"type", "quad"}, {"corners", {{-w, 0, -w}, {-w, 0, w}, {w, 0, w}, {w, 0, -w}}}, {"material", "wall"}}};
  scene["lights"] = {{{"type", "directional"}, {"direction", {0, -1, 0}}, {"color", {1, 1, 1}}}};
  const IrradianceField field = fieldOf(test::sceneFromJson(scene.dump()), {16, 1024});
  const glm::vec3 p(0.3f, 1.0f, -0.2f);
  for (const glm::vec3 n : {glm::vec3(0, -1, 0), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::vec3(0, -0.6f, 0.8f)}) {
    const float expected = 0.5f * kPi * (1.0f - n.y) / 2.0f;
    const IrradianceField::Lookup got = field.irradiance(p, n);
    std::printf("normal (%g, %g, %g): %.4f, expected %.4f\n", n.x, n.y, n.z, got.irradiance.x, expected);
    EXPECT_NEAR(got.irradiance.x, expected, 0.03f * kPi);
  }
}

// Two rooms side by side, a thin wall between them: the left one's walls
// emit, the right one's do not. The probes next to the wall on its left see
// the wall nearer than a point on the right, so their light does not reach
// the right room's floor, which stays dark (or, where too few probes see
// it, is left to the tracer).
TEST(IrradianceField, LightDoesNotLeakThroughAThinWall) {
  json scene = emittingBox(0.0, 0.5);
  json objects = json::array();
  auto quad = [&](std::vector<std::vector<double>> c, const char* m) {
    objects.push_back({{"type", "quad"}, {"corners", c}, {"material", m}});
  };
  quad({{0, 0, 0}, {4, 0, 0}, {4, 0, 2}, {0, 0, 2}}, "wall");    // floor
  quad({{0, 2, 0}, {0, 2, 2}, {4, 2, 2}, {4, 2, 0}}, "wall");    // ceiling
  quad({{0, 0, 0}, {0, 2, 0}, {4, 2, 0}, {4, 0, 0}}, "wall");    // back
  quad({{0, 0, 2}, {4, 0, 2}, {4, 2, 2}, {0, 2, 2}}, "wall");    // front
  quad({{0, 0, 0}, {0, 0, 2}, {0, 2, 2}, {0, 2, 0}}, "glow");    // the left room's far wall
  quad({{4, 0, 0}, {4, 2, 0}, {4, 2, 2}, {4, 0, 2}}, "wall");    // the right room's far wall
  quad({{2, 0, 0}, {2, 2, 0}, {2, 2, 2}, {2, 0, 2}}, "wall");    // between them
  scene["objects"] = objects;
  scene["materials"]["glow"] = {{"color", {1, 1, 1}}, {"diffuse", 0.5}, {"emission", {1, 1, 1}}};
  const IrradianceField field = fieldOf(test::sceneFromJson(scene.dump()), {8, 256});
  const glm::vec3 up(0, 1, 0);
  for (const float z : {0.3f, 1.0f, 1.7f}) {
    const IrradianceField::Lookup lit = field.irradiance({1.9f, 0.0f, z}, up);
    const IrradianceField::Lookup dark = field.irradiance({2.1f, 0.0f, z}, up);
    std::printf("floor at z %.1f: %.4f left of the wall, %.5f right (%s)\n", z, lit.irradiance.x,
                dark.irradiance.x, dark.decided ? "decided" : "undecided");
    EXPECT_GT(lit.irradiance.x, 0.05f);
    EXPECT_TRUE(!dark.decided || dark.irradiance.x < 0.01f * lit.irradiance.x);
  }
}

// Probes filled in batches, in any order, hold the bytes of probes filled
// at once.
TEST(IrradianceField, BatchesFillTheSameBytes) {
  const Scene scene = test::sceneFromJson(emittingBox(1.0, 0.5).dump());
  const PreparedScene prepared(scene, BvhSettings{});
  const FieldSettings settings{3, 64};
  RayStats stats;
  const IrradianceField whole = buildField(prepared, scene.frame, settings, stats);
  IrradianceField batched(scene.geometry.bounds(), settings);
  const int n = batched.probeCount();
  fillProbes(batched, prepared, scene.frame, n / 2, n, stats);
  fillProbes(batched, prepared, scene.frame, 0, n / 2, stats);
  for (int i = 0; i < n; ++i) {
    ASSERT_EQ(std::memcmp(&whole.probe(i), &batched.probe(i), sizeof(IrradianceField::Probe)), 0) << "probe " << i;
  }
}

// The frame as the hybrid frame's tracer makes it: Whitted's direct light
// with the field's indirect light (a path where the field cannot decide).
LinearImage renderWithField(const Scene& scene, const IrradianceField& field, RayStats& stats) {
  const PreparedScene prepared(scene, BvhSettings{});
  const Renderer renderer(prepared, scene.frame, EffectPlan::derive(scene, scene.frame), &field);
  ThreadPool pool(2);
  return renderLinear(renderer, pool, stats, LinearRange::kUnbounded, {});
}

double meanOf(const LinearImage& image) {
  double sum = 0.0;
  for (const float v : image.rgb) sum += v;
  return sum / static_cast<double>(image.rgb.size());
}

// Inside the emitting box of albedo 0.5, the camera sees a wall's emission
// and what it reflects: 1 + 0.5 E / pi, E the walls' emission (pi, its 12
// triangles' in closed form, 64 shadow rays each) and the field's reflected light
// (0.9375 pi), the 1.96875 of the path trace's four bounces.
TEST(IrradianceField, TheTracerAddsTheFieldsLightWherePathsWouldBring) {
  json box = emittingBox(1.0, 0.5);
  box["sampling"] = {{"pattern", "sobol"}, {"samples", 64}, {"light_samples", 768}};
  const Scene scene = test::sceneFromJson(box.dump());
  const IrradianceField field = fieldOf(scene, {4, 256});
  RayStats stats;
  const double withField = meanOf(renderWithField(scene, field, stats));
  const double paths = meanOf(test::renderLinearFrame(scene));
  std::printf("emitting box: %.4f with the field, %.4f path traced, expected 1.96875\n", withField, paths);
  EXPECT_NEAR(withField, 1.96875, 0.02);
  EXPECT_NEAR(paths, 1.96875, 0.02);
  // The field decides nearly everywhere: a few samples in the corners,
  // where a probe's map is in doubt, go to the path tracer.
  EXPECT_LE(stats.fieldUndecided, stats.primary / 100);
}

// Where the field cannot decide, the sample is the path trace's own: with
// a field whose every probe sits inside an object (each sees a wall at once
// in every direction), no lookup decides, and the frame is the path trace.
TEST(IrradianceField, WhereTheFieldCannotDecideThePixelIsThePathTraces) {
  json box = emittingBox(1.0, 0.5);
  box["sampling"] = {{"samples", 4}};
  const Scene scene = test::sceneFromJson(box.dump());
  IrradianceField blind(scene.geometry.bounds(), {4, 64});
  for (int i = 0; i < blind.probeCount(); ++i) blind.probe(i).moments.fill(glm::vec2(1e-4f, 1e-8f));
  RayStats stats;
  const LinearImage withField = renderWithField(scene, blind, stats);
  const LinearImage paths = test::renderLinearFrame(scene);
  EXPECT_EQ(stats.fieldUndecided, stats.paths);
  EXPECT_GT(stats.fieldUndecided, 0u);
  EXPECT_EQ(withField.rgb, paths.rgb);
}

}  // namespace
}  // namespace glint
