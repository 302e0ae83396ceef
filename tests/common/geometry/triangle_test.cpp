#include "common/geometry/triangle.h"

#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(Triangle, HitGivesDistanceAndBarycentrics) {
  const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const auto hit = intersectTriangle(Ray({0.25f, 0.5f, 2.0f}, {0, 0, -1}), a, b, c, 100.0f);
  ASSERT_TRUE(hit);
  EXPECT_FLOAT_EQ(hit->t, 2.0f);
  EXPECT_FLOAT_EQ(hit->b0, 0.25f);
  EXPECT_FLOAT_EQ(hit->b1, 0.25f);
  EXPECT_FLOAT_EQ(hit->b2, 0.5f);
  // Both windings, both sides.
  EXPECT_TRUE(intersectTriangle(Ray({0.25f, 0.5f, -2.0f}, {0, 0, 1}), a, c, b, 100.0f));
  EXPECT_FALSE(intersectTriangle(Ray({0.75f, 0.75f, 2.0f}, {0, 0, -1}), a, b, c, 100.0f));
  EXPECT_FALSE(intersectTriangle(Ray({0.25f, 0.5f, 2.0f}, {0, 0, 1}), a, b, c, 100.0f));  // behind
  EXPECT_FALSE(intersectTriangle(Ray({0.25f, 0.5f, 2.0f}, {0, 0, -1}), a, b, c, 1.5f));   // beyond tMax
}

// Rays aimed at points of the shared diagonal of a unit square made of two
// triangles. Where the float ray (computed exactly, in double) crosses the
// square's plane inside the square, it must hit at least one triangle (a
// miss is a crack), at the right distance.
void expectWatertightDiagonal(const glm::vec3& shift, int rays) {
  const glm::vec3 p00 = shift + glm::vec3(0, 0, 0), p10 = shift + glm::vec3(1, 0, 0);
  const glm::vec3 p11 = shift + glm::vec3(1, 1, 0), p01 = shift + glm::vec3(0, 1, 0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_real_distribution<float> spread(-3.0f, 3.0f);
  int misses = 0;
  int badT = 0;
  int checked = 0;
  for (int i = 0; i < rays; ++i) {
    const float s = unit(rng);
    const glm::vec3 target = shift + glm::vec3(s, s, 0.0f);
    const glm::vec3 origin = target + glm::vec3(spread(rng), spread(rng), 1.0f + unit(rng) * 4.0f);
    const Ray ray(origin, glm::normalize(target - origin));
    // Where this very ray meets the plane, in double precision.
    const glm::dvec3 o(ray.o), d(ray.d);
    const double t = (double(shift.z) - o.z) / d.z;
    const glm::dvec3 p = o + t * d - glm::dvec3(shift);
    const double margin = 1e-3;
    if (p.x < margin || p.y < margin || p.x > 1.0 - margin || p.y > 1.0 - margin) continue;
    ++checked;
    auto h = intersectTriangle(ray, p00, p10, p11, 1e30f);
    if (!h) h = intersectTriangle(ray, p00, p11, p01, 1e30f);
    if (!h) {
      ++misses;
    } else if (std::abs(h->t - t) > 1e-6 * (t + glm::length(glm::dvec3(shift)))) {
      ++badT;
    }
  }
  EXPECT_EQ(misses, 0);
  EXPECT_EQ(badT, 0);
  EXPECT_GT(checked, rays * 9 / 10);
}

TEST(Triangle, SharedEdgeIsWatertight) { expectWatertightDiagonal(glm::vec3(0.0f), 1'000'000); }

TEST(Triangle, SharedEdgeIsWatertightFarFromOrigin) {
  expectWatertightDiagonal(glm::vec3(148376.0f, 1234.0f, -223423.0f), 1'000'000);
}

// Rays exactly through the centre vertex of a fan of 8 triangles all hit.
void expectFanCentreHit(const glm::vec3& shift) {
  const glm::vec3 centre = shift;
  glm::vec3 rim[8];
  for (int k = 0; k < 8; ++k) {
    const float a = static_cast<float>(k) * 0.785398163f;
    rim[k] = shift + glm::vec3(std::cos(a), std::sin(a), 0.0f);
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> spread(-2.0f, 2.0f);
  int misses = 0;
  for (int i = 0; i < 100'000; ++i) {
    const glm::vec3 origin = centre + glm::vec3(spread(rng), spread(rng), 0.5f + std::abs(spread(rng)));
    const Ray ray(origin, glm::normalize(centre - origin));
    bool hit = false;
    for (int k = 0; k < 8 && !hit; ++k) hit = intersectTriangle(ray, centre, rim[k], rim[(k + 1) % 8], 1e30f).has_value();
    misses += hit ? 0 : 1;
  }
  EXPECT_EQ(misses, 0);
}

TEST(Triangle, FanCentreVertexIsWatertight) { expectFanCentreHit(glm::vec3(0.0f)); }
TEST(Triangle, FanCentreVertexIsWatertightFarFromOrigin) {
  expectFanCentreHit(glm::vec3(148376.0f, 1234.0f, -223423.0f));
}

TEST(Triangle, DegenerateTrianglesNeverHitNorGiveNaN) {
  const float nan = std::nanf("");
  const Ray ray({0.2f, 0.2f, 1.0f}, {0, 0, -1});
  EXPECT_FALSE(intersectTriangle(ray, {0, 0, 0}, {1, 1, 0}, {2, 2, 0}, 1e30f));  // collinear
  EXPECT_FALSE(intersectTriangle(ray, {0, 0, 0}, {0, 0, 0}, {1, 1, 0}, 1e30f));  // repeated vertex
  EXPECT_FALSE(intersectTriangle(ray, {0.2f, 0.2f, 0}, {0.2f, 0.2f, 0}, {0.2f, 0.2f, 0}, 1e30f));  // a point
  EXPECT_FALSE(intersectTriangle(ray, {nan, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1e30f));
  // Edge-on: the ray lies in the triangle's plane.
  EXPECT_FALSE(intersectTriangle(Ray({-1.0f, 0.2f, 0.0f}, {1, 0, 0}), {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1e30f));
}

}  // namespace
}  // namespace glint
