#include "common/geometry/region_query.h"

#include <random>

#include <gtest/gtest.h>

namespace glint {
namespace {

// The cube [0, 1]^3 as a region: six planes, eight corners.
ConvexRegion unitCube() {
  ConvexRegion r;
  for (int axis = 0; axis < 3; ++axis) {
    glm::vec3 n(0.0f);
    n[axis] = 1.0f;
    r.planes.emplace_back(n, 1.0f);
    r.planes.emplace_back(-n, 0.0f);
  }
  for (int i = 0; i < 8; ++i) r.corners.emplace_back(i & 1, i >> 1 & 1, i >> 2 & 1);
  for (const glm::vec3& c : r.corners) r.box.expand(c);
  r.slack = 1e-6f;
  return r;
}

Geometry oneTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  Geometry g;
  g.addMesh(MeshInput{{a, b, c}, {}, {}, {0, 1, 2}, 0, {}});
  return g;
}

bool holds(const Geometry& g, const ConvexRegion& r, std::uint32_t skip = ~0u) {
  return !primitivesInRegion(Bvh::build(g, BvhSettings{}), g, r, skip).empty();
}

TEST(RegionQuery, TriangleInsideOrCrossingIsFound) {
  const ConvexRegion cube = unitCube();
  EXPECT_TRUE(holds(oneTriangle({0.2f, 0.2f, 0.5f}, {0.8f, 0.2f, 0.5f}, {0.5f, 0.8f, 0.5f}), cube));
  // Larger than the cube, cutting through it: no vertex inside.
  EXPECT_TRUE(
      holds(oneTriangle({-5.0f, -5.0f, 0.5f}, {5.0f, -5.0f, 0.5f}, {0.0f, 5.0f, 0.5f}), cube));
}

TEST(RegionQuery, SeparatedTrianglesAreNot) {
  const ConvexRegion cube = unitCube();
  // Beyond one face of the cube.
  EXPECT_FALSE(
      holds(oneTriangle({2.0f, 0.0f, 0.0f}, {3.0f, 1.0f, 0.0f}, {2.5f, 0.0f, 1.0f}), cube));
  // Its box overlaps the cube's, but the triangle's plane (x + y = 2.5)
  // leaves every corner on one side.
  EXPECT_FALSE(
      holds(oneTriangle({2.5f, 0.0f, -1.0f}, {0.0f, 2.5f, -1.0f}, {1.25f, 1.25f, 2.0f}), cube));
  // The skipped primitive is never reported.
  EXPECT_FALSE(
      holds(oneTriangle({0.2f, 0.2f, 0.5f}, {0.8f, 0.2f, 0.5f}, {0.5f, 0.8f, 0.5f}), cube, 0));
}

TEST(RegionQuery, SharedCornersTouchWithoutEntering) {
  ConvexRegion cube = unitCube();
  // A triangle in the cube's face z = 1 plane, outside it but for the corner
  // (1, 1, 1) it shares.
  const Geometry touching = oneTriangle({1.0f, 1.0f, 1.0f}, {2.0f, 1.0f, 1.0f}, {1.0f, 2.0f, 1.0f});
  EXPECT_TRUE(holds(touching, cube));  // on the face plane: may be inside
  cube.shared = {{1.0f, 1.0f, 1.0f}};
  // Now the corner counts as outside the planes through it: the triangle's
  // other vertices lie beyond x = 1 or y = 1, but not beyond the same plane,
  // so only the triangle's own plane (z = 1, every corner on or below) can
  // separate it, and it cannot (four corners lie in it): still found.
  EXPECT_TRUE(holds(touching, cube));
  // Lifted off the face plane except at the shared corner: separated by x = 1.
  EXPECT_FALSE(
      holds(oneTriangle({1.0f, 1.0f, 1.0f}, {2.0f, 0.5f, 1.5f}, {2.0f, 0.2f, 0.5f}), cube));
}

// An open base (the plane a receiver lies in, here the cube's face x = 1):
// a triangle lying in it touches the region without entering; one a little
// inside enters.
TEST(RegionQuery, OpenBaseLetsCoplanarTrianglesTouch) {
  ConvexRegion cube = unitCube();
  const Geometry inFace = oneTriangle({1.0f, 0.2f, 0.2f}, {1.0f, 0.8f, 0.2f}, {1.0f, 0.5f, 0.8f});
  EXPECT_TRUE(holds(inFace, cube));
  cube.openBase = true;
  EXPECT_FALSE(holds(inFace, cube));
  EXPECT_TRUE(
      holds(oneTriangle({0.99f, 0.2f, 0.2f}, {0.99f, 0.8f, 0.2f}, {0.99f, 0.5f, 0.8f}), cube));
  // Not the other planes: in the face y = 1 it still counts.
  EXPECT_TRUE(holds(oneTriangle({0.2f, 1.0f, 0.2f}, {0.8f, 1.0f, 0.2f}, {0.5f, 1.0f, 0.8f}), cube));
}

TEST(RegionQuery, SpheresBySeparatingPlane) {
  const ConvexRegion cube = unitCube();
  Geometry near;
  near.addSphere({{1.5f, 0.5f, 0.5f}, 0.6f, 0});  // reaches x = 0.9
  EXPECT_TRUE(holds(near, cube));
  Geometry far;
  far.addSphere({{1.5f, 0.5f, 0.5f}, 0.4f, 0});  // stops at x = 1.1
  EXPECT_FALSE(holds(far, cube));
}

// Against brute force: for each of many random triangles, whenever one of
// the points sampled on it lies in the cube, the query reports it. Then the
// BVH walk: a soup of every triangle reported clear and one reported is
// clear without that one and not with it.
TEST(RegionQuery, AgreesWithSampledPointsOnRandomTriangles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> pos(-1.5f, 2.5f);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const ConvexRegion cube = unitCube();
  MeshInput clear, found;
  for (int t = 0; t < 300; ++t) {
    const glm::vec3 v0(pos(rng), pos(rng), pos(rng)), v1(pos(rng), pos(rng), pos(rng)),
        v2(pos(rng), pos(rng), pos(rng));
    const bool reported = holds(oneTriangle(v0, v1, v2), cube);
    bool inside = false;
    for (int s = 0; s < 4000 && !inside; ++s) {
      float a = unit(rng), b = unit(rng);
      if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
      const glm::vec3 p = v0 + a * (v1 - v0) + b * (v2 - v0);
      inside = p.x > 0.0f && p.x < 1.0f && p.y > 0.0f && p.y < 1.0f && p.z > 0.0f && p.z < 1.0f;
    }
    if (inside) {
      EXPECT_TRUE(reported) << "triangle " << t;
    }
    MeshInput& to = reported ? found : clear;
    for (const glm::vec3& v : {v0, v1, v2}) {
      to.positions.push_back(v);
      to.indices.push_back(static_cast<std::uint32_t>(to.indices.size()));
    }
  }
  ASSERT_GT(clear.indices.size(), 3u * 30);
  ASSERT_GT(found.indices.size(), 3u * 30);
  Geometry soup;
  soup.addMesh(clear);
  soup.addMesh(MeshInput{
      {found.positions[0], found.positions[1], found.positions[2]}, {}, {}, {0, 1, 2}, 0, {}});
  const auto last = static_cast<std::uint32_t>(soup.triangles().size() - 1);
  EXPECT_FALSE(holds(soup, cube, last));
  EXPECT_TRUE(holds(soup, cube));
}

}  // namespace
}  // namespace glint
