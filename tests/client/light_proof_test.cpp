#include "client/raster/light_proof.h"

#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace glint::gl {
namespace {

// Whether the segment from p to the light crosses any primitive but `self`,
// testing every primitive: the reference the proof is held to.
bool blocked(const Geometry& g, std::uint32_t self, const glm::vec3& p, const glm::vec3& light) {
  const float distance = glm::length(light - p);
  const Ray ray(p, (light - p) / distance);
  for (std::uint32_t prim = 0; prim < g.primitiveCount(); ++prim) {
    if (prim != self && g.intersect(prim, ray, distance)) return true;
  }
  return false;
}

struct Checked {
  int proven = 0;       // (primitive, light) pairs with no spot
  int spotted = 0;      // pairs with one
  int outsideSpot = 0;  // points sampled on a spotted triangle outside its spot
};

const ShadowSpot* spotOf(const LightProof& proof, std::uint32_t prim, int light) {
  for (const ShadowSpot& s : proof.spots) {
    if (s.prim == prim && s.light == light) return &s;
  }
  return nullptr;
}

// Whether p (in the spot's plane) lies in a triangle's spot: the rectangle
// corners[0], corners[1] - corners[0], corners[2] - corners[0].
bool inSpot(const ShadowSpot& spot, const glm::vec3& p) {
  for (int side : {1, 2}) {
    const glm::vec3 edge = spot.corners[static_cast<std::size_t>(side)] - spot.corners[0];
    const float along = glm::dot(p - spot.corners[0], edge), length2 = glm::dot(edge, edge);
    if (length2 > 0.0f && (along < 0.0f || along > length2)) return false;
  }
  return true;
}

// For every casting light: no shadow ray from 200 points on a primitive
// with no spot (a triangle's interior, a sphere's side facing the light), nor
// from a point on a triangle outside its spot, to that light is blocked.
Checked expectProofHolds(const Scene& scene, const LightProof& proof) {
  const Geometry& g = scene.geometry;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.001f, 0.999f);
  Checked c;
  for (int l = 0; l < static_cast<int>(scene.lights.size()); ++l) {
    const glm::vec3& light = scene.lights[static_cast<std::size_t>(l)].position;
    for (std::uint32_t i = 0; i < g.triangles().size(); ++i) {
      const ShadowSpot* spot = spotOf(proof, i, l);
      (spot ? c.spotted : c.proven)++;
      const Triangle& t = g.triangles()[i];
      const glm::vec3 a = g.positions()[t.v[0]], b = g.positions()[t.v[1]],
                      d = g.positions()[t.v[2]];
      for (int s = 0; s < 200; ++s) {
        float u = unit(rng), v = unit(rng);
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        const glm::vec3 p = a + u * (b - a) + v * (d - a);
        if (spot && inSpot(*spot, p)) continue;
        c.outsideSpot += spot ? 1 : 0;
        if (blocked(g, i, p, light)) {
          ADD_FAILURE() << "triangle " << i << " is shadowed from light " << l
                        << " outside its spot";
          return c;
        }
      }
    }
    for (std::uint32_t i = 0; i < g.spheres().size(); ++i) {
      const auto self = static_cast<std::uint32_t>(g.triangles().size()) + i;
      const bool spotted = spotOf(proof, self, l) != nullptr;
      (spotted ? c.spotted : c.proven)++;
      if (spotted) continue;
      const Sphere& sphere = g.spheres()[i];
      for (int s = 0; s < 200; ++s) {
        glm::vec3 n = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)) - 0.5f);
        if (glm::dot(n, light - sphere.centre) < 0.0f) n = -n;
        const glm::vec3 p = sphere.centre + n * sphere.radius * 1.0001f;
        if (glm::dot(n, light - p) <= 0.0f) continue;  // the unlit side: no direct light to prove
        if (blocked(g, self, p, light)) {
          ADD_FAILURE() << "sphere " << i << " with no spot is shadowed from light " << l;
          return c;
        }
      }
    }
  }
  return c;
}

// An n x n grid of squares in the plane y = 0, vertices shared.
MeshInput floorGrid(int n, float size) {
  MeshInput mesh;
  for (int z = 0; z <= n; ++z) {
    for (int x = 0; x <= n; ++x)
      mesh.positions.emplace_back(size * x / n - size / 2, 0.0f, size * z / n - size / 2);
  }
  for (int z = 0; z < n; ++z) {
    for (int x = 0; x < n; ++x) {
      const auto i = static_cast<std::uint32_t>(z * (n + 1) + x),
                 w = static_cast<std::uint32_t>(n + 1);
      mesh.indices.insert(mesh.indices.end(), {i, i + 1, i + w, i + 1, i + w + 1, i + w});
    }
  }
  return mesh;
}

Scene withLights(Geometry g, std::vector<glm::vec3> lights) {
  Scene scene;
  scene.geometry = std::move(g);
  for (const glm::vec3& p : lights) scene.lights.push_back(Light{.position = p});
  return scene;
}

std::vector<bool> allCast(const Scene& scene) {
  return std::vector<bool>(scene.lights.size(), true);
}

// A floor of 16 x 16 squares, neighbours sharing edges, with a ball above
// it: the floor away from the ball's shadow is proved lit (its neighbours
// touch each tetrahedron at shared corners only), the squares under the
// ball are not, and the ball itself is.
TEST(LightProof, FloorAndBall) {
  Geometry g;
  g.addMesh(floorGrid(16, 8.0f));
  g.addSphere({{0.0f, 1.0f, 0.0f}, 0.5f, 0});
  const Scene scene = withLights(std::move(g), {{0.0f, 4.0f, 0.0f}});
  const LightProof proof = LightProof::prove(scene, allCast(scene));
  const Checked c = expectProofHolds(scene, proof);
  EXPECT_GT(c.proven, 400);  // of the 512 triangles and the ball
  EXPECT_GT(c.spotted, 10);  // the ball's shadow is about 1.3 across
  EXPECT_GT(c.outsideSpot, 100);
  EXPECT_EQ(spotOf(proof, 512, 0), nullptr);
  // The triangles right under the ball are in its shadow: each has a spot
  // holding its centre.
  for (std::uint32_t i = 0; i < scene.geometry.triangles().size(); ++i) {
    const Triangle& t = scene.geometry.triangles()[i];
    const glm::vec3 centre =
        (scene.geometry.positions()[t.v[0]] + scene.geometry.positions()[t.v[1]] +
         scene.geometry.positions()[t.v[2]]) /
        3.0f;
    if (glm::length(centre) > 0.4f) continue;
    const ShadowSpot* spot = spotOf(proof, i, 0);
    EXPECT_TRUE(spot && inSpot(*spot, centre)) << i;
  }
}

// Random triangles and spheres, three lights: nothing is shadowed outside
// its spots, and the proof is not empty.
TEST(LightProof, RandomSoupsAreLitOutsideTheirSpots) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-10.0f, 10.0f), size(0.2f, 2.0f);
    Geometry g;
    MeshInput mesh;
    for (int i = 0; i < 120; ++i) {
      const glm::vec3 c(pos(rng), pos(rng), pos(rng));
      for (int k = 0; k < 3; ++k) {
        mesh.positions.push_back(c + size(rng) * glm::vec3(pos(rng), pos(rng), pos(rng)) / 10.0f);
        mesh.indices.push_back(static_cast<std::uint32_t>(mesh.positions.size() - 1));
      }
    }
    g.addMesh(std::move(mesh));
    for (int i = 0; i < 20; ++i) g.addSphere({{pos(rng), pos(rng), pos(rng)}, size(rng) * 0.5f, 0});
    const Scene scene =
        withLights(std::move(g), {{0.0f, 0.0f, 0.0f}, {12.0f, 3.0f, -4.0f}, {-3.0f, 15.0f, 6.0f}});
    const Checked c = expectProofHolds(scene, LightProof::prove(scene, allCast(scene)));
    EXPECT_GT(c.proven, 100) << seed;
    EXPECT_GT(c.spotted, 10) << seed;
    EXPECT_GT(c.outsideSpot, 1000) << seed;
  }
}

// A light in a triangle's plane spots the whole triangle (with no plane); a
// light inside a sphere spots the whole sphere; a light that casts no
// shadows spots nothing.
TEST(LightProof, DegenerateCasesSpotTheWholePrimitive) {
  Geometry g;
  g.addMesh(MeshInput{{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {}, {}, {0, 1, 2}, 0, {}});
  g.addSphere({{5.0f, 5.0f, 5.0f}, 1.0f, 0});
  // In the triangle's plane; inside the sphere; casting none; above both.
  const Scene scene =
      withLights(std::move(g), {{3, 0, 3}, {5.0f, 5.2f, 5.0f}, {0, 3, 0}, {0.3f, 2.0f, 0.3f}});
  const LightProof proof = LightProof::prove(scene, {true, true, false, true});
  const ShadowSpot* inPlane = spotOf(proof, 0, 0);
  ASSERT_NE(inPlane, nullptr);
  EXPECT_EQ(inPlane->plane, glm::vec4(0.0f));
  for (const glm::vec3 p :
       {glm::vec3(0.01f, 0, 0.01f), glm::vec3(0.98f, 0, 0.01f), glm::vec3(0.01f, 0, 0.98f)}) {
    EXPECT_TRUE(inSpot(*inPlane, p));
  }
  EXPECT_NE(spotOf(proof, 0, 1), nullptr);  // the sphere holding the light is in the way
  EXPECT_EQ(spotOf(proof, 0, 2), nullptr);
  EXPECT_EQ(spotOf(proof, 0, 3), nullptr);
  EXPECT_EQ(spotOf(proof, 1, 0), nullptr);
  ASSERT_NE(spotOf(proof, 1, 1), nullptr);
  EXPECT_EQ(spotOf(proof, 1, 1)->cornerCount, 8);
  EXPECT_EQ(spotOf(proof, 1, 2), nullptr);
  EXPECT_EQ(spotOf(proof, 1, 3), nullptr);
}

}  // namespace
}  // namespace glint::gl
