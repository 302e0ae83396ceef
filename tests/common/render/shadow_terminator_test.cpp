// The shadow terminator of a coarse mesh with smooth normals: where the
// light turns to shadow it must follow the smooth surface the normals
// describe, as on the analytic sphere, not the flat triangles' edges.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <nlohmann/json.hpp>

#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;
constexpr int kSize = 200;
// The material's colour x ambient, as a linear byte: a pixel in shadow.
constexpr int kShadowByte = 23;  // round(255 x 0.9 x 0.1)

json terminatorScene(const json& object, const json& light) {
  return {{"glint", 1},
          {"image", {{"width", kSize}, {"height", kSize}, {"encoding", "linear"}}},
          {"camera", {{"eye", {0, 0, 4}}, {"look_at", {0, 0, 0}}, {"fov_y", 35}}},
          {"materials", {{"m", {{"color", {0.9, 0.9, 0.9}}, {"ambient", 0.1}, {"diffuse", 1.0}}}}},
          {"lights", {light}},
          {"objects", {object}}};
}

// The unit sphere as an icosphere of 320 triangles (about 20 degrees apart),
// each vertex's normal the sphere's.
json coarseSmoothSphere() {
  const MeshInput mesh = test::icosphere(2, glm::vec3(0.0f), 1.0f);
  json positions = json::array(), normals = json::array();
  for (const glm::vec3& p : mesh.positions) {
    const glm::vec3 n = glm::normalize(p);
    positions.insert(positions.end(), {p.x, p.y, p.z});
    normals.insert(normals.end(), {n.x, n.y, n.z});
  }
  return {
      {"type", "mesh"}, {"positions", positions}, {"normals", normals}, {"indices", mesh.indices}, {"material", "m"}};
}

// The lit pixels beside a pixel in shadow (4-neighbours): the terminator.
std::vector<glm::ivec2> terminator(const FrameImage& image) {
  std::vector<glm::ivec2> pixels;
  const auto at = [&](int x, int y) { return test::pixelAt(image, x, y).r; };
  for (int y = 1; y + 1 < kSize; ++y) {
    for (int x = 1; x + 1 < kSize; ++x) {
      if (at(x, y) <= kShadowByte) continue;
      if (at(x - 1, y) == kShadowByte || at(x + 1, y) == kShadowByte || at(x, y - 1) == kShadowByte ||
          at(x, y + 1) == kShadowByte) {
        pixels.push_back({x, y});
      }
    }
  }
  return pixels;
}

// How far each of `pixels` lies from the nearest of `curve`'s: the largest
// and the mean, in pixels.
struct Distances {
  double largest = 0.0;
  double mean = 0.0;
};
Distances distancesTo(const std::vector<glm::ivec2>& pixels, const std::vector<glm::ivec2>& curve) {
  Distances d;
  for (const glm::ivec2& p : pixels) {
    double nearest = 1e9;
    for (const glm::ivec2& q : curve) nearest = std::min(nearest, glm::length(glm::dvec2(p - q)));
    d.largest = std::max(d.largest, nearest);
    d.mean += nearest / static_cast<double>(pixels.size());
  }
  return d;
}

// The sphere is 85 pixels in radius, its triangles' edges about 25 pixels
// long. Where a triangle's plane turns from the light its normals may still
// catch it: left dark (the light behind the flat triangle adding nothing),
// or shadowed by the triangle itself (shadow rays from the flat triangle),
// the terminator was a saw of triangles, up to 14.3 and 9.1 pixels off the
// analytic one (2.4 and 1.4 on average). With shadow rays from the point
// lifted onto the smooth surface (Geometry::lifted) it stays within 2.
TEST(ShadowTerminator, ACoarseSmoothSphereHasTheAnalyticSpheresTerminator) {
  const json sphere = {{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "m"}};
  const json lights[] = {{{"type", "directional"}, {"direction", {-1, -0.3, 0.25}}},
                         {{"type", "point"}, {"position", {6, 1.5, -1}}}};
  for (const json& light : lights) {
    const FrameImage analytic = test::render(test::sceneFromJson(terminatorScene(sphere, light).dump())).image;
    const FrameImage mesh =
        test::render(test::sceneFromJson(terminatorScene(coarseSmoothSphere(), light).dump())).image;
    const std::vector<glm::ivec2> expected = terminator(analytic);
    const std::vector<glm::ivec2> got = terminator(mesh);
    ASSERT_GT(expected.size(), 100u) << light;
    ASSERT_GT(got.size(), 100u) << light;
    const Distances d = distancesTo(got, expected);
    std::printf("%s light: %zu terminator pixels, %.1f px from the analytic at most, %.2f on average\n",
                light["type"].get<std::string>().c_str(), got.size(), d.largest, d.mean);
    EXPECT_LE(d.largest, 3.0) << light;
    EXPECT_LE(d.mean, 1.0) << light;
  }
}

}  // namespace
}  // namespace glint
