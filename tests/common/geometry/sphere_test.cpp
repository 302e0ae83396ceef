#include "common/geometry/sphere.h"

#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(Sphere, NearRootFromOutsideFarRootFromInside) {
  const Sphere s{{0, 0, 0}, 1.0f, 0};
  EXPECT_FLOAT_EQ(*intersectSphere(s, Ray({0, 0, 5}, {0, 0, -1}), 1e30f), 4.0f);
  EXPECT_FLOAT_EQ(*intersectSphere(s, Ray({0, 0, 0}, {0, 0, -1}), 1e30f), 1.0f);
  EXPECT_FALSE(intersectSphere(s, Ray({0, 0, 5}, {0, 0, 1}), 1e30f));      // behind
  EXPECT_FALSE(intersectSphere(s, Ray({0, 2, 5}, {0, 0, -1}), 1e30f));     // beside
  EXPECT_FALSE(intersectSphere(s, Ray({0, 0, 5}, {0, 0, -1}), 3.5f));      // beyond tMax
}

TEST(Sphere, RayJustInsideTakesFarRootNeverNonPositive) {
  const Sphere s{{0.3f, -0.2f, 0.1f}, 2.0f, 0};
  std::mt19937 rng(3);
  std::normal_distribution<float> g;
  for (int i = 0; i < 100'000; ++i) {
    glm::vec3 n = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    const glm::vec3 origin = s.centre + n * (s.radius * 0.999999f);
    const glm::vec3 d = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    const auto t = intersectSphere(s, Ray(origin, d), 1e30f);
    ASSERT_TRUE(t) << i;
    ASSERT_GT(*t, 0.0f);
  }
}

// Hit or miss agrees with a double-precision reference (except within a hair
// of tangency) for a tiny sphere far away, and the hit lies on the sphere.
void expectAgreesWithDouble(float radius, float distance) {
  const glm::dvec3 centre(0.0, 0.0, -static_cast<double>(distance));
  const Sphere s{glm::vec3(centre), radius, 0};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> offset(-2.0 * radius, 2.0 * radius);
  int disagreements = 0;
  double worst = 0.0;
  for (int i = 0; i < 100'000; ++i) {
    const glm::dvec3 target = centre + glm::dvec3(offset(rng), offset(rng), 0.0);
    const glm::dvec3 d = glm::normalize(target);
    const Ray ray(glm::vec3(0.0f), glm::vec3(d));
    // Reference in double, with the float ray's direction.
    const glm::dvec3 df(ray.d);
    const double b = glm::dot(centre, df);
    const glm::dvec3 l = centre - b * df;
    const double disc = double(radius) * radius - glm::dot(l, l);
    const auto t = intersectSphere(s, ray, 1e30f);
    if (std::abs(disc) < 1e-6 * double(radius) * radius) continue;  // tangent: either answer
    if ((disc > 0.0) != t.has_value()) ++disagreements;
    if (t) {
      const glm::dvec3 p = glm::dvec3(ray.o) + double(*t) * df;
      worst = std::max(worst, std::abs(glm::length(p - centre) - radius));
    }
  }
  EXPECT_EQ(disagreements, 0);
  // Within a few ulps of the hit distance (the coordinates' own precision).
  EXPECT_LT(worst, 8.0 * std::ldexp(1.0, std::ilogb(distance) - 23));
}

TEST(Sphere, TinySphereFarAwayAgreesWithDouble) {
  expectAgreesWithDouble(1e-3f, 1e4f);
  expectAgreesWithDouble(1e-3f, 50.0f);
}

TEST(Sphere, HugeSphereAgreesWithDouble) { expectAgreesWithDouble(1e6f, 1e6f + 1.0f); }

TEST(Sphere, HugeSphereAsFloor) {
  const Sphere floor{{0.0f, -1e6f, 0.0f}, 1e6f, 0};
  const auto t = intersectSphere(floor, Ray({0.0f, 1.0f, 0.0f}, {0.0f, -1.0f, 0.0f}), 1e30f);
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, 1.0f, 0.07f);  // ulp(1e6) = 0.0625
}

TEST(Sphere, ProjectionPutsPointOnSurface) {
  const Sphere s{{1, 2, 3}, 0.5f, 0};
  const glm::vec3 p = projectToSphere(s, {1.0f, 2.0f, 4.0f});
  EXPECT_NEAR(glm::length(p - s.centre), 0.5f, 1e-6f);
}

}  // namespace
}  // namespace glint
