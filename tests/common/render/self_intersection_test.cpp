// Secondary rays leave a surface without hitting it again, and yet thin
// geometry right behind the surface is still found.
#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "common/geometry/bvh.h"
#include "common/render/optics.h"
#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

glm::vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> g;
  return glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
}

// Spheres and transformed triangles at coordinates up to 1e5.
Geometry scatteredPrimitives(std::mt19937& rng, int count) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(0, 5);
  Geometry g;
  MeshInput mesh;
  for (int i = 0; i < count; ++i) {
    const float magnitude = std::pow(10.0f, static_cast<float>(exponent(rng)));
    const glm::vec3 centre = magnitude * (2.0f * glm::vec3(unit(rng), unit(rng), unit(rng)) - 1.0f);
    const float size = magnitude * (0.05f + unit(rng)) + 1.0f;
    g.addSphere({centre, size, 0});
    // A triangle rotated about a random axis, scaled and moved to the same place.
    glm::mat4 m = glm::translate(glm::mat4(1.0f), centre + 3.0f * size * randomUnit(rng));
    m = glm::rotate(m, 6.2831853f * unit(rng), randomUnit(rng));
    m = glm::scale(m, glm::vec3(size * (0.5f + unit(rng)), size * (0.5f + unit(rng)), 1.0f));
    for (const glm::vec3 p : {glm::vec3(-1, -1, 0), glm::vec3(1, -1, 0), glm::vec3(0, 1, 0)}) {
      mesh.positions.push_back(glm::vec3(m * glm::vec4(p, 1.0f)));
      mesh.indices.push_back(static_cast<std::uint32_t>(mesh.positions.size() - 1));
    }
  }
  g.addMesh(std::move(mesh));
  return g;
}

// From 10^6 hit points on spheres (from outside) and triangles (either side),
// rays leaving into the hemisphere of the normal never hit their own surface.
TEST(SelfIntersection, RaysLeavingASurfaceNeverHitIt) {
  std::mt19937 rng(17);
  const Geometry g = scatteredPrimitives(rng, 1000);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_int_distribution<std::uint32_t> pick(0, g.primitiveCount() - 1);
  int hitPoints = 0;
  int selfHits = 0;
  while (hitPoints < 1'000'000) {
    const std::uint32_t prim = pick(rng);
    const Bounds3 b = g.primitiveBounds(prim);
    const float size = glm::length(b.extent());
    // Aim at a random point of the primitive's box from a few sizes away.
    const glm::vec3 target = b.min + glm::vec3(unit(rng), unit(rng), unit(rng)) * b.extent();
    const glm::vec3 origin = target + 2.0f * size * randomUnit(rng);
    const Ray ray(origin, glm::normalize(target - origin));
    const auto hit = g.intersect(prim, ray, 1e30f);
    if (!hit) continue;
    ++hitPoints;
    const SurfaceHit s = g.surface(ray, *hit);
    glm::vec3 d = randomUnit(rng);
    if (glm::dot(d, s.ng) < 0.0f) d = -d;
    const auto again = g.intersect(prim, Ray(offsetRayOrigin(s.p, s.error, s.ng), d), 1e30f);
    if (again) {
      ++selfHits;
      ADD_FAILURE() << (g.isSphere(prim) ? "sphere" : "triangle") << " size " << size << " at (" << s.p.x << ", "
                    << s.p.y << ", " << s.p.z << ") hit again at t = " << again->t << ", d.ng = " << glm::dot(d, s.ng);
    }
  }
  EXPECT_EQ(selfHits, 0);
}

// ...and the offset is small enough that a shell 1e-4 thick inside a unit
// sphere is still hit by a ray continuing into the sphere.
TEST(SelfIntersection, ThinShellBehindTheSurfaceIsStillHit) {
  Geometry g;
  g.addSphere({{0.3f, -0.2f, 0.5f}, 1.0f, 0});
  g.addSphere({{0.3f, -0.2f, 0.5f}, 1.0f - 1e-4f, 0});
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> offset(-0.95f, 0.95f);
  int misses = 0;
  for (int i = 0; i < 100'000; ++i) {
    const glm::vec3 axis = randomUnit(rng);
    glm::vec3 side = glm::normalize(glm::cross(axis, randomUnit(rng)));
    const glm::vec3 target = glm::vec3(0.3f, -0.2f, 0.5f) + offset(rng) * side;
    const glm::vec3 origin = target + 5.0f * axis;
    const Ray ray(origin, -axis);
    const auto outer = g.intersect(0, ray, 1e30f);
    ASSERT_TRUE(outer);
    const SurfaceHit s = g.surface(ray, *outer);
    const auto inner = g.intersect(1, Ray(offsetRayOrigin(s.p, s.error, -s.ng), ray.d), 1e30f);
    misses += inner ? 0 : 1;
  }
  EXPECT_EQ(misses, 0);
}

// A lit plane far from the origin: no shadow ray is blocked by the plane
// itself. (The sphere under the plane only makes shadow rays necessary.)
TEST(SelfIntersection, LitPlaneFarFromOriginCastsNoShadowOnItself) {
  const Scene s = loadSceneFile(test::sourcePath("scenes/hard/far-plane.json"));
  ASSERT_TRUE(EffectPlan::derive(s).shadows);
  const FrameResult r = test::render(s, 2);
  EXPECT_GT(r.stats.shadow, 1000u);
  EXPECT_EQ(r.stats.shadowBlocked, 0u);
}

}  // namespace
}  // namespace glint
