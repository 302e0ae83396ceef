// Geometry::lifted: the point shadow rays leave from, moved from a flat
// triangle onto the smooth surface its vertex normals describe.
#include <cmath>
#include <optional>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "common/geometry/geometry.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

// A hit on triangle `prim` at barycentric weights (b1, b2), seen along the
// ray from `from`.
struct SeenHit {
  Hit hit;
  SurfaceHit s;
};
std::optional<SeenHit> hitOn(const Geometry& g, std::uint32_t prim, float b1, float b2, const glm::vec3& from) {
  const Triangle& t = g.triangles()[prim];
  const glm::vec3 p =
      (1.0f - b1 - b2) * g.positions()[t.v[0]] + b1 * g.positions()[t.v[1]] + b2 * g.positions()[t.v[2]];
  const Ray ray(from, glm::normalize(p - from));
  const std::optional<Hit> hit = g.intersect(prim, ray, 1e30f);
  if (!hit) return std::nullopt;
  return SeenHit{*hit, g.surface(ray, *hit)};
}

// The unit icosphere of 320 triangles at `centre`, its normals the sphere's
// (pointing in with `inward`).
Geometry smoothSphere(const glm::vec3& centre, bool inward = false) {
  MeshInput mesh = test::icosphere(2, centre, 1.0f);
  for (const glm::vec3& p : mesh.positions)
    mesh.normals.push_back((inward ? -1.0f : 1.0f) * glm::normalize(p - centre));
  Geometry g;
  g.addMesh(std::move(mesh));
  return g;
}

// Seen from outside, every point of every triangle moves out, onto the
// sphere the normals describe or past it, by no more than it lay inside: the
// flat triangle's point lies up to 1.8 % of the radius inside the
// sphere; lifted, it lies at most as far outside (the corners' tangent
// planes, blended, overshoot the sphere as Phong tessellation does), so a
// shadow ray from it clears the neighbouring triangles that bend away.
TEST(LiftedPoint, ASmoothSpheresTrianglesRiseOntoTheSphere) {
  const Geometry g = smoothSphere(glm::vec3(0.0f));
  std::mt19937 random(7);
  std::uniform_real_distribution<float> u(0.02f, 0.98f);
  float deepest = 0.0f, highest = 0.0f;
  for (std::uint32_t prim = 0; prim < g.triangles().size(); ++prim) {
    for (int k = 0; k < 8; ++k) {
      float b1 = u(random), b2 = u(random);
      if (b1 + b2 > 0.98f) std::tie(b1, b2) = std::make_pair(0.98f - b1, 0.98f - b2);
      const glm::vec3 centroid = (g.positions()[g.triangles()[prim].v[0]] + g.positions()[g.triangles()[prim].v[1]] +
                                  g.positions()[g.triangles()[prim].v[2]]) /
                                 3.0f;
      const std::optional<SeenHit> h = hitOn(g, prim, b1, b2, 3.0f * centroid);
      ASSERT_TRUE(h) << prim;
      const Geometry::LiftedPoint lifted = g.lifted(h->hit, h->s);
      const float inside = 1.0f - glm::length(h->s.p);
      const float outside = glm::length(lifted.p) - 1.0f;
      EXPECT_GT(glm::dot(lifted.p - h->s.p, h->s.ng), 0.0f) << prim;
      EXPECT_GE(outside, -1e-6f) << prim;
      EXPECT_LE(outside, inside) << prim;
      EXPECT_GE(lifted.error, h->s.error);
      deepest = std::max(deepest, inside);
      highest = std::max(highest, outside);
    }
  }
  std::printf("flat points up to %.4f inside the sphere, lifted up to %.4f outside\n", deepest, highest);
}

// Normals that bend away from the viewer (the inside of a bowl) and a flat
// triangle's normals leave the point where it is: lifting only ever moves a
// point up to a convex surface.
TEST(LiftedPoint, ConcaveAndFlatTrianglesStayWhereTheyAre) {
  const Geometry bowl = smoothSphere(glm::vec3(0.0f), true);
  const std::optional<SeenHit> inside = hitOn(bowl, 5, 0.3f, 0.3f, glm::vec3(0.0f));
  ASSERT_TRUE(inside);
  const Geometry::LiftedPoint fromInside = bowl.lifted(inside->hit, inside->s);
  EXPECT_EQ(fromInside.p, inside->s.p);
  EXPECT_EQ(fromInside.error, inside->s.error);

  Geometry flat;
  MeshInput square;
  square.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  square.normals.assign(4, glm::vec3(0, 0, 1));
  square.indices = {0, 1, 2, 0, 2, 3};
  flat.addMesh(std::move(square));
  for (std::uint32_t prim = 0; prim < 2; ++prim) {
    const std::optional<SeenHit> h = hitOn(flat, prim, 0.3f, 0.3f, glm::vec3(0.5f, 0.5f, 2.0f));
    ASSERT_TRUE(h);
    EXPECT_EQ(flat.lifted(h->hit, h->s).p, h->s.p);
  }
}

}  // namespace
}  // namespace glint
