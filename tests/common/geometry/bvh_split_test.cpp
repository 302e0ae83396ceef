// The builder's four-lane split pieces (common/geometry/bvh_split.h) against the
// scalar arithmetic they replace: Bounds3::expand and Bounds3::centre for the
// boxes, the binned SAH's scalar bin formula, std::partition's order. The
// builder promises the tree the scalar code made, byte for byte.
#include "common/geometry/bvh_split.h"
#include "common/math/float_bits.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace glint {
namespace {

// Boxes of every kind the builder meets: random, flat (a zero extent on an
// axis), a point, repeated boxes, signed zeros; ids from 0 (whose bits are a
// subnormal float) to the largest; those with ids divisible by 3 tested
// alone (spheres), the others not.
std::vector<BuildPrimitive> somePrimitives(std::vector<Bounds3>& boxes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coord(-100.0f, 100.0f), size(0.0f, 5.0f);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 lo(coord(rng), coord(rng), coord(rng));
    glm::vec3 hi = lo + glm::vec3(size(rng), size(rng), size(rng));
    if (i % 7 == 0) hi.y = lo.y;
    if (i % 11 == 0) hi = lo;
    boxes.push_back({lo, hi});
  }
  boxes.push_back({{-0.0f, 0.0f, -0.0f}, {0.0f, -0.0f, 0.0f}});
  boxes.push_back(boxes[5]);
  std::vector<BuildPrimitive> prims;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const std::uint32_t id = i + 1 == boxes.size() ? 0xffffffffu : static_cast<std::uint32_t>(i);
    prims.emplace_back(boxes[i], id, i % 3 == 0);
  }
  return prims;
}

bool sameBits(const Bounds3& a, const Bounds3& b) {
  return std::memcmp(&a.min, &b.min, sizeof(glm::vec3)) == 0 && std::memcmp(&a.max, &b.max, sizeof(glm::vec3)) == 0;
}

TEST(BvhSplit, BoxesAndCentresAreTheScalarOnes) {
  std::vector<Bounds3> boxes;
  const std::vector<BuildPrimitive> prims = somePrimitives(boxes);
  Bounds3 bounds, centroids;
  NodeBox box;
  for (std::size_t i = 0; i < prims.size(); ++i) {
    ASSERT_TRUE(sameBits(prims[i].box.bounds(), boxes[i])) << i;
    const Float4 c = prims[i].box.centre();
    const glm::vec3 expected = boxes[i].centre();
    ASSERT_EQ(std::memcmp(&c, &expected, sizeof(glm::vec3)), 0) << i;
    EXPECT_EQ(c[3], 0.0f) << "the id's lane takes no part";
    bounds.expand(boxes[i]);
    centroids.expand(expected);
    box.add(prims[i]);
  }
  EXPECT_TRUE(sameBits(box.bounds.bounds(), bounds));
  EXPECT_TRUE(sameBits(box.centroids.bounds(), centroids));
  EXPECT_EQ(prims.back().id(), 0xffffffffu);
  EXPECT_EQ(prims.front().id(), 0u);
}

// The SAH's sweep prices the bins' unions by Box4::surfaceArea: the scalar
// one's bits, on each box, on unions of growing size, and on the empty box.
TEST(BvhSplit, SurfaceAreasAreTheScalarOnes) {
  std::vector<Bounds3> boxes;
  const std::vector<BuildPrimitive> prims = somePrimitives(boxes);
  Box4 grown = Box4::empty();
  Bounds3 scalarGrown;
  EXPECT_EQ(floatToBits(grown.surfaceArea()), floatToBits(scalarGrown.surfaceArea()));
  for (std::size_t i = 0; i < prims.size(); ++i) {
    ASSERT_EQ(floatToBits(prims[i].box.surfaceArea()), floatToBits(boxes[i].surfaceArea())) << i;
    grown.expand(prims[i].box);
    scalarGrown.expand(boxes[i]);
    ASSERT_EQ(floatToBits(grown.surfaceArea()), floatToBits(scalarGrown.surfaceArea())) << i;
  }
}

TEST(BvhSplit, BinsAreTheScalarFormulasOnEveryAxis) {
  std::vector<Bounds3> boxes;
  const std::vector<BuildPrimitive> prims = somePrimitives(boxes);
  Bounds3 centroids;
  for (const Bounds3& b : boxes) centroids.expand(b.centre());
  for (int bins : {2, 16, 64}) {
    const BinGrid grid(NodeBox::of(prims).centroids, bins);
    for (std::size_t i = 0; i < prims.size(); ++i) {
      const Int4 lanes = grid.binOf(prims[i]);
      for (int a = 0; a < 3; ++a) {
        const float c = boxes[i].centre()[a], lo = centroids.min[a], extent = centroids.max[a] - lo;
        const int scalar = std::clamp(static_cast<int>((c - lo) * (static_cast<float>(bins) / extent)), 0, bins - 1);
        ASSERT_EQ(lanes[a], scalar) << "primitive " << i << " axis " << a << " bins " << bins;
      }
    }
  }
}

// Centroids within an ulp of the planes between bins, where the order of
// the operations decides the bin: each must land where the scalar formula puts it.
TEST(BvhSplit, BinsOnThePlanesAreTheScalarFormulas) {
  const Bounds3 range{{-3.7f, 0.1f, 1000.3f}, {91.3f, 0.1f + 1e-3f, 1013.9f}};
  std::vector<BuildPrimitive> prims;
  std::vector<glm::vec3> points;
  for (int bins : {3, 7, 16, 64}) {
    for (int k = 0; k <= bins; ++k) {
      const glm::vec3 plane = range.min + (static_cast<float>(k) / static_cast<float>(bins)) * range.extent();
      for (float toward : {-kInfinity, 0.0f, kInfinity}) {
        glm::vec3 p;
        for (int a = 0; a < 3; ++a) p[a] = toward == 0.0f ? plane[a] : std::nextafter(plane[a], toward);
        points.push_back(p);
      }
    }
  }
  points.push_back(range.min);
  points.push_back(range.max);
  for (const glm::vec3& p : points) prims.emplace_back(Bounds3{p, p}, 0u, false);
  const NodeBox box = NodeBox::of(prims);
  const Bounds3 centroids = box.centroids.bounds();
  int checked = 0;
  for (int bins : {3, 7, 16, 64}) {
    const BinGrid grid(box.centroids, bins);
    for (std::size_t i = 0; i < prims.size(); ++i) {
      const Int4 lanes = grid.binOf(prims[i]);
      for (int a = 0; a < 3; ++a) {
        const float lo = centroids.min[a], extent = centroids.max[a] - lo;
        const float scale = static_cast<float>(bins) / extent;
        const int scalar = std::clamp(static_cast<int>((points[i][a] - lo) * scale), 0, bins - 1);
        ASSERT_EQ(lanes[a], scalar) << "point " << i << " axis " << a << " bins " << bins;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

// Binning twice into the same bins (emptied in between): each bin's count
// and, where it holds any, the scalar union of its primitives' boxes.
TEST(BvhSplit, BinsHoldTheirCountsAndTheScalarUnionOfTheirBoxes) {
  std::vector<Bounds3> boxes;
  const std::vector<BuildPrimitive> prims = somePrimitives(boxes);
  SahBins bins;
  for (int round = 0; round < 2; ++round) {
    const int binCount = round == 0 ? 64 : 5;
    const BinGrid grid(NodeBox::of(prims).centroids, binCount);
    bins.reset(binCount);
    bins.add(prims, grid);
    for (int a = 0; a < 3; ++a) {
      std::vector<int> counts(binCount, 0);
      std::vector<Bounds3> unions(binCount);
      for (std::size_t i = 0; i < prims.size(); ++i) {
        const int b = grid.binOf(prims[i])[a];
        ++counts[b];
        unions[b].expand(boxes[i]);
      }
      for (int b = 0; b < binCount; ++b) {
        ASSERT_EQ(bins.counts[a][b], counts[b]) << "round " << round << " axis " << a << " bin " << b;
        if (counts[b] > 0) {
          EXPECT_TRUE(sameBits(bins.bounds[a][b].bounds(), unions[b])) << "axis " << a << " bin " << b;
        }
      }
    }
  }
}

TEST(BvhSplit, PartitionIsStdPartitionsOrderAndMeasuresBothSides) {
  std::vector<Bounds3> boxes;
  const std::vector<BuildPrimitive> prims = somePrimitives(boxes);
  for (float plane : {-150.0f, -30.0f, 0.0f, 12.5f, 150.0f}) {
    const auto isLeft = [plane](const BuildPrimitive& p) { return p.box.centre()[0] < plane; };
    std::vector<BuildPrimitive> expected = prims, actual = prims;
    const auto mid = static_cast<std::size_t>(std::partition(expected.begin(), expected.end(), isLeft) - expected.begin());
    std::array<NodeBox, 2> sides;
    ASSERT_EQ(partitionMeasured(actual, isLeft, sides), mid) << plane;
    for (std::size_t i = 0; i < prims.size(); ++i) ASSERT_EQ(actual[i].id(), expected[i].id()) << plane << " at " << i;
    std::array<Bounds3, 2> bounds, centroids;
    std::array<bool, 2> blocksOnly = {true, true};
    for (std::size_t i = 0; i < actual.size(); ++i) {
      const Bounds3 b = actual[i].box.bounds();
      bounds[i < mid ? 0 : 1].expand(b);
      centroids[i < mid ? 0 : 1].expand(b.centre());
      if (actual[i].id() % 3 == 0) blocksOnly[i < mid ? 0 : 1] = false;  // somePrimitives' alone ones
    }
    for (int side = 0; side < 2; ++side) {
      EXPECT_TRUE(sameBits(sides[side].bounds.bounds(), bounds[side])) << plane << " side " << side;
      EXPECT_TRUE(sameBits(sides[side].centroids.bounds(), centroids[side])) << plane << " side " << side;
      EXPECT_EQ(sides[side].blocksOnly(), blocksOnly[side]) << plane << " side " << side;
    }
  }
}

}  // namespace
}  // namespace glint
