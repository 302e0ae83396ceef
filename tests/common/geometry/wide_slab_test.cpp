// The traversal's robust slab test (common/geometry/wide_slab.h), one box at a time
// in any of a node's lanes, the other lanes empty; four lanes per
// instruction and, where the CPU has AVX2, eight, with the same bits.
#include "common/geometry/wide_slab.h"

#include <cmath>
#include <cstring>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/math/float_bits.h"

namespace glint {
namespace {

const Bounds3 kUnit{{0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}};

struct SlabResult {
  unsigned lanes;
  alignas(32) float entry[kBvhWidth];
};

template <typename V>
[[gnu::always_inline]] inline SlabResult slabs(const WideBoxes& boxes, const Ray& ray, float tMax) {
  SlabResult r;
  r.lanes = intersectSlabs(boxes, SlabRay<V>(ray), 0.0f, tMax, r.entry);
  return r;
}

#if defined(__x86_64__)
GLINT_AVX2 SlabResult slabsEight(const WideBoxes& boxes, const Ray& ray, float tMax) {
  return slabs<Float8>(boxes, ray, tMax);
}
#endif

// Whether the ray enters `box` (in lane `lane`) before tMax; *entry gets the
// entry distance. An empty lane is never hit. The eight-lane instruction,
// where this CPU has it, gives the same lanes and entry bits.
bool hitsBox(const Bounds3& box, const Ray& ray, float tMax, float* entry = nullptr, int lane = 0) {
  WideBoxes boxes;
  for (int i = 0; i < kBvhWidth; ++i) boxes.set(i, i == lane ? box : Bounds3{});
  const SlabResult four = slabs<Float4>(boxes, ray, tMax);
#if defined(__x86_64__)
  if (avx2Available()) {
    const SlabResult eight = slabsEight(boxes, ray, tMax);
    EXPECT_EQ(eight.lanes, four.lanes);
    EXPECT_EQ(std::memcmp(eight.entry, four.entry, sizeof four.entry), 0) << "entries differ";
  }
#endif
  EXPECT_EQ(four.lanes & ~(1u << lane), 0u) << "an empty lane was hit";
  if (entry) *entry = four.entry[lane];
  return (four.lanes & (1u << lane)) != 0;
}

TEST(Slab, HitGivesEntry) {
  float entry = -7.0f;
  ASSERT_TRUE(hitsBox(kUnit, Ray({-1.0f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}), 100.0f, &entry));
  EXPECT_FLOAT_EQ(entry, 1.0f);
  EXPECT_FALSE(hitsBox(kUnit, Ray({-1.0f, 0.5f, 0.5f}, {-1.0f, 0.0f, 0.0f}), 100.0f));
  EXPECT_FALSE(hitsBox(kUnit, Ray({-1.0f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}), 0.5f));
  // The ray ends inside the box: still a hit.
  EXPECT_TRUE(hitsBox(kUnit, Ray({-1.0f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}), 1.5f));
}

// Rays parallel to two axes, with +0.0 and -0.0 in those components, from
// origins before, inside and after the box along the travel axis and inside,
// on a face plane, on an edge or outside across it: the expected hit or miss
// and never a NaN. Boundaries count as inside.
TEST(Slab, AxisParallelRaysWithSignedZerosAndOriginsOnPlanes) {
  const float across[] = {-1.0f, 0.0f, 0.5f, 1.0f, 2.0f};
  const float along[] = {-1.0f, 0.0f, 0.5f, 1.0f, 2.0f};
  int cases = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const int a1 = (axis + 1) % 3;
    const int a2 = (axis + 2) % 3;
    for (float travel : {1.0f, -1.0f}) {
      for (float z1 : {0.0f, -0.0f}) {
        for (float z2 : {0.0f, -0.0f}) {
          for (float c1 : across) {
            for (float c2 : across) {
              for (float s : along) {
                glm::vec3 o, d;
                o[axis] = s;
                o[a1] = c1;
                o[a2] = c2;
                d[axis] = travel;
                d[a1] = z1;
                d[a2] = z2;
                const bool insideAcross = c1 >= 0.0f && c1 <= 1.0f && c2 >= 0.0f && c2 <= 1.0f;
                const bool reaches = travel > 0.0f ? s <= 1.0f : s >= 0.0f;
                float entry = -7.0f;
                const bool got = hitsBox(kUnit, Ray(o, d), 1e30f, &entry, cases % kBvhWidth);
                EXPECT_EQ(got, insideAcross && reaches)
                    << "axis " << axis << " travel " << travel << " origin " << o.x << "," << o.y << ","
                    << o.z << " zeros " << std::signbit(z1) << std::signbit(z2);
                if (got) {
                  EXPECT_FALSE(std::isnan(entry));
                  EXPECT_GE(entry, 0.0f);
                }
                ++cases;
              }
            }
          }
        }
      }
    }
  }
  EXPECT_EQ(cases, 3 * 2 * 4 * 125);
}

TEST(Slab, RayThroughCornerAndAlongEdge) {
  // Exactly through the corner (1, 1, 1) diagonally.
  EXPECT_TRUE(hitsBox(kUnit, Ray({2.0f, 2.0f, 2.0f}, glm::vec3(-1.0f) / std::sqrt(3.0f)), 1e30f));
  // Along the edge y = 0, z = 0.
  float entry = -7.0f;
  ASSERT_TRUE(hitsBox(kUnit, Ray({-1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, -0.0f}), 1e30f, &entry, 6));
  EXPECT_FALSE(std::isnan(entry));
}

// A box of a float step around a point of the ray, computed in double and
// widened by that computation's error bound, so that the exact point lies
// inside: the test must report the hit however the distances round.
// Origins far from zero and directions with tiny components stress the
// rounding; a test without the far scale misses.
TEST(Slab, NeverCullsABoxAroundAPointOfTheRay) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> exponent(-30.0f, 4.0f);
  std::uniform_real_distribution<double> along(0.0, 100.0);
  for (int i = 0; i < 200000; ++i) {
    glm::vec3 o, d;
    for (int axis = 0; axis < 3; ++axis) {
      o[axis] = unit(rng) * std::exp2(std::round(exponent(rng)));
      d[axis] = unit(rng) * (i % 3 == axis ? std::exp2(-std::round(std::abs(exponent(rng)))) : 1.0f);
    }
    const Ray ray(o, glm::normalize(d));
    const double t = along(rng);
    Bounds3 box;
    for (int axis = 0; axis < 3; ++axis) {
      const double origin = ray.o[axis], step = t * static_cast<double>(ray.d[axis]);
      const double p = origin + step, error = 0x1p-50 * (std::abs(origin) + std::abs(step));
      box.min[axis] = std::nextafter(static_cast<float>(p - error), -kInfinity);
      box.max[axis] = std::nextafter(static_cast<float>(p + error), kInfinity);
    }
    ASSERT_TRUE(hitsBox(box, ray, 1e30f, nullptr, i % kBvhWidth)) << "ray " << i << " at t " << t;
  }
}

}  // namespace
}  // namespace glint
