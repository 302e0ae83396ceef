#include "common/bounds.h"
#include "common/wide_slab.h"

#include <cmath>

#include <gtest/gtest.h>

namespace glint {
namespace {

const Bounds3 kUnit{{0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}};

TEST(Bounds, DefaultIsEmptyAndUnionNeedsNoSpecialCase) {
  Bounds3 b;
  EXPECT_TRUE(b.empty());
  EXPECT_EQ(b.surfaceArea(), 0.0f);
  b.expand(glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_FALSE(b.empty());
  EXPECT_EQ(b.min, glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(b.max, glm::vec3(1.0f, 2.0f, 3.0f));
  b.expand(Bounds3{{0.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 2.0f}});
  EXPECT_EQ(b.max, glm::vec3(2.0f, 2.0f, 3.0f));
  EXPECT_FLOAT_EQ(b.surfaceArea(), 2.0f * (2 * 2 + 2 * 3 + 3 * 2));
}

TEST(Slab, HitGivesEntryAndExit) {
  SlabHit hit{};
  ASSERT_TRUE(intersectSlabs(kUnit, Ray({-1.0f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}), 0.0f, 100.0f, &hit));
  EXPECT_FLOAT_EQ(hit.t0, 1.0f);
  EXPECT_NEAR(hit.t1, 2.0f, 1e-5f);
  EXPECT_FALSE(intersectSlabs(kUnit, Ray({-1.0f, 0.5f, 0.5f}, {-1.0f, 0.0f, 0.0f}), 0.0f, 100.0f, nullptr));
  EXPECT_FALSE(intersectSlabs(kUnit, Ray({-1.0f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}), 0.0f, 0.5f, nullptr));
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
                SlabHit hit{-7.0f, -7.0f};
                const bool got = intersectSlabs(kUnit, Ray(o, d), 0.0f, 1e30f, &hit);
                // The traversal's 4-lane form decides the same, in whichever lane the box is.
                const int lane = cases % 4;
                Boxes4 boxes;
                for (int i = 0; i < 4; ++i) boxes.set(i, i == lane ? kUnit : Bounds3{});
                Float4 entry;
                const unsigned lanes = intersectSlabs4(boxes, SlabRay4(Ray(o, d)), 0.0f, 1e30f, &entry);
                EXPECT_EQ(lanes, got ? 1u << lane : 0u);
                if (got) {
                  EXPECT_EQ(entry[lane], hit.t0);
                }
                EXPECT_EQ(got, insideAcross && reaches)
                    << "axis " << axis << " travel " << travel << " origin " << o.x << "," << o.y << ","
                    << o.z << " zeros " << std::signbit(z1) << std::signbit(z2);
                if (got) {
                  EXPECT_FALSE(std::isnan(hit.t0));
                  EXPECT_FALSE(std::isnan(hit.t1));
                  EXPECT_LE(hit.t0, hit.t1);
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
  EXPECT_TRUE(intersectSlabs(kUnit, Ray({2.0f, 2.0f, 2.0f}, glm::vec3(-1.0f) / std::sqrt(3.0f)), 0.0f,
                             1e30f, nullptr));
  // Along the edge y = 0, z = 0.
  SlabHit hit{};
  ASSERT_TRUE(intersectSlabs(kUnit, Ray({-1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, -0.0f}), 0.0f, 1e30f, &hit));
  EXPECT_FALSE(std::isnan(hit.t0) || std::isnan(hit.t1));
}

}  // namespace
}  // namespace glint
