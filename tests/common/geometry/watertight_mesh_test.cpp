// Closed meshes have no cracks, and their sidedness comes from geometry.
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/geometry/bvh.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

void expectNoCrack(const glm::vec3& centre, float innerRadius) {
  Geometry g;
  g.addMesh(test::icosphere(4, centre, 1.0f));  // 5,120 triangles
  const Bvh bvh = Bvh::build(g, {});
  std::mt19937 rng(31);
  std::normal_distribution<float> n;
  std::uniform_real_distribution<float> r(0.0f, innerRadius);
  int misses = 0;
  for (int i = 0; i < 1'000'000; ++i) {
    const glm::vec3 origin = centre + r(rng) * glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
    const Ray ray(origin, glm::normalize(glm::vec3(n(rng), n(rng), n(rng))));
    misses += bvh.intersect(ray, 1e30f) ? 0 : 1;
  }
  EXPECT_EQ(misses, 0);
}

// 10^6 random rays from inside a closed mesh all hit it: a miss is a crack.
TEST(WatertightMesh, RaysFromInsideAClosedMeshAllHit) { expectNoCrack(glm::vec3(0.0f), 0.9f); }
TEST(WatertightMesh, RaysFromInsideAClosedMeshFarFromOriginAllHit) {
  expectNoCrack(glm::vec3(148376.0f, 1234.0f, -223423.0f), 0.5f);
}

nlohmann::json glassMeshScene(bool flipped) {
  MeshInput mesh = test::icosphere(2, glm::vec3(0.0f, 0.8f, 0.0f), 0.8f);
  if (flipped) {
    for (std::size_t i = 0; i < mesh.indices.size(); i += 3) std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
  }
  nlohmann::json positions = nlohmann::json::array();
  for (const glm::vec3& p : mesh.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
  return {{"glint", 1},
          {"image", {{"width", 96}, {"height", 72}}},
          {"camera", {{"eye", {0.3, 1.5, 3.5}}, {"look_at", {0, 0.7, 0}}, {"fov_y", 40}}},
          {"sampling", {{"pattern", "jittered"}, {"samples", 2}}},
          {"tracing", {{"max_depth", 8}}},
          {"textures", {{"c", {{"type", "checker"}, {"colors", {{1, 1, 1}, {0.8, 0.1, 0.1}}}, {"scale", 8}}}}},
          {"materials",
           {{"floor", {{"texture", "c"}, {"ambient", 0.2}, {"diffuse", 0.8}}},
            {"glass", {{"ambient", 0}, {"diffuse", 0.05}, {"specular", 0.5}, {"shininess", 200},
                       {"reflectivity", 0.1}, {"transparency", 0.85}, {"ior", 1.5}}}}},
          {"lights", {{{"type", "point"}, {"position", {-2, 4, 3}}}}},
          {"objects",
           {{{"type", "quad"}, {"corners", {{-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4}}}, {"uvs", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}}, {"material", "floor"}},
            {{"type", "mesh"}, {"positions", positions}, {"indices", mesh.indices}, {"material", "glass"}}}}};
}

// Flipping the winding of a closed glass mesh changes nothing in the image:
// inside and outside are decided from the path, not from a stored normal.
TEST(WatertightMesh, FlippedWindingGivesTheSameImage) {
  const FrameResult a = test::render(test::sceneFromJson(glassMeshScene(false).dump()), 2);
  const FrameResult b = test::render(test::sceneFromJson(glassMeshScene(true).dump()), 2);
  EXPECT_EQ(a.image.rgb, b.image.rgb);
  EXPECT_GT(a.stats.refraction, 1000u);
  EXPECT_EQ(a.stats.nonFiniteSamples, 0u);
}

}  // namespace
}  // namespace glint
