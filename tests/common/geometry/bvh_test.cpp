#include "common/geometry/bvh.h"

#include <cmath>
#include <cstring>
#include <random>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace glint {
namespace {

// Nearest hit by testing every primitive: the reference for the BVH.
std::optional<Hit> bruteForce(const Geometry& g, const Ray& ray) {
  std::optional<Hit> best;
  float tMax = 1e30f;
  for (std::uint32_t p = 0; p < g.primitiveCount(); ++p) {
    const auto h = g.intersect(p, ray, best ? std::nextafter(tMax, 1e30f) : tMax);
    if (h && (!best || closerHit(*h, *best))) {
      best = h;
      tMax = h->t;
    }
  }
  return best;
}

Geometry randomSoup(int triangles, int spheres, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-10.0f, 10.0f);
  std::uniform_real_distribution<float> size(0.05f, 1.5f);
  Geometry g;
  MeshInput mesh;
  for (int i = 0; i < triangles; ++i) {
    const glm::vec3 c(pos(rng), pos(rng), pos(rng));
    for (int k = 0; k < 3; ++k) {
      mesh.positions.push_back(c + size(rng) * glm::vec3(pos(rng), pos(rng), pos(rng)) / 10.0f);
      mesh.indices.push_back(static_cast<std::uint32_t>(mesh.positions.size() - 1));
    }
  }
  g.addMesh(std::move(mesh));
  for (int i = 0; i < spheres; ++i) g.addSphere({{pos(rng), pos(rng), pos(rng)}, size(rng) * 0.5f, 0});
  return g;
}

// A mesh whose vertices lie on exact binary fractions (an 8 x 8 grid of
// squares, heights varying), so that many triangles touch node faces exactly.
Geometry gridMesh() {
  Geometry g;
  MeshInput mesh;
  constexpr int kN = 8;
  for (int z = 0; z <= kN; ++z) {
    for (int x = 0; x <= kN; ++x) {
      mesh.positions.emplace_back(x * 0.25f, ((x * 7 + z * 3) % 5) * 0.125f, z * 0.25f);
    }
  }
  for (int z = 0; z < kN; ++z) {
    for (int x = 0; x < kN; ++x) {
      const std::uint32_t i = static_cast<std::uint32_t>(z * (kN + 1) + x);
      mesh.indices.insert(mesh.indices.end(), {i, i + 1, i + kN + 1, i + 1, i + kN + 2, i + kN + 1});
    }
  }
  g.addMesh(std::move(mesh));
  return g;
}

// The primitives of every leaf lane of every node: each primitive exactly
// once, a leaf of at most maxLeafSize; a block leaf holds two to
// kBlockTriangles triangles, each lane's vertices those of its triangle bit
// for bit, the unused lanes zero. Returns the number of block leaves.
int expectEachPrimitiveInOneLeaf(const Geometry& g, const Bvh& bvh, int maxLeafSize) {
  std::vector<int> seen(g.primitiveCount(), 0);
  int blockLeaves = 0;
  for (const BvhNode& node : bvh.nodes()) {
    for (int lane = 0; lane < node.children; ++lane) {
      const std::uint32_t count = node.count[lane] & ~kBlockLeaf;
      if (node.count[lane] == 0) continue;
      EXPECT_LE(count, static_cast<std::uint32_t>(maxLeafSize));
      if (!(node.count[lane] & kBlockLeaf)) {
        for (std::uint32_t i = node.offset[lane]; i < node.offset[lane] + count; ++i) ++seen.at(bvh.primIds().at(i));
        continue;
      }
      ++blockLeaves;
      EXPECT_GE(count, 2u);
      const TriangleBlock& block = bvh.blocks()[node.offset[lane]];
      for (std::uint32_t k = 0; k < kBlockTriangles; ++k) {
        TriangleLanes expected{};
        if (k < count) {
          const std::uint32_t prim = block.prims[k];
          ++seen.at(prim);
          if (g.isSphere(prim)) {
            ADD_FAILURE() << "sphere " << prim << " in a block";
            continue;
          }
          const Triangle& t = g.triangles()[prim];
          expected.set(static_cast<int>(k), g.positions()[t.v[0]], g.positions()[t.v[1]], g.positions()[t.v[2]]);
        }
        for (int v = 0; v < 3; ++v) {
          for (int axis = 0; axis < 3; ++axis) {
            EXPECT_EQ(std::memcmp(&block.vertices.v[v][axis][k], &expected.v[v][axis][k], sizeof(float)), 0);
          }
        }
      }
    }
  }
  for (int count : seen) EXPECT_EQ(count, 1);
  return blockLeaves;
}

std::vector<Ray> randomRays(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-14.0f, 14.0f);
  std::normal_distribution<float> dir;
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    rays.emplace_back(glm::vec3(pos(rng), pos(rng), pos(rng)),
                      glm::normalize(glm::vec3(dir(rng), dir(rng), dir(rng))));
  }
  return rays;
}

// The nearest hit with both box test widths (eight runs as four where the
// CPU lacks AVX2), which must agree bit for bit; returns it.
std::optional<Hit> intersectBothWidths(const Bvh& bvh, const Ray& ray) {
  const auto four = bvh.intersect(ray, 1e30f, BoxTestWidth::kFour);
  const auto eight = bvh.intersect(ray, 1e30f, BoxTestWidth::kEight);
  EXPECT_EQ(four.has_value(), eight.has_value());
  if (four && eight) {
    EXPECT_EQ(std::memcmp(&*four, &*eight, sizeof(Hit)), 0);
  }
  return eight;
}

bool occludedBothWidths(const Bvh& bvh, const Ray& ray) {
  const bool four = bvh.occluded(ray, 1e30f, BoxTestWidth::kFour);
  EXPECT_EQ(four, bvh.occluded(ray, 1e30f, BoxTestWidth::kEight));
  return four;
}

class BvhBuilders : public ::testing::TestWithParam<BvhBuilder> {};

TEST_P(BvhBuilders, NearestHitAndOcclusionEqualBruteForce) {
  const Geometry g = randomSoup(1000, 50, 1);
  BvhSettings settings;
  settings.builder = GetParam();
  const Bvh bvh = Bvh::build(g, settings);
  EXPECT_LE(bvh.depth(), kBvhMaxDepth);
  EXPECT_EQ(bvh.primIds().size(), g.primitiveCount());
  int hits = 0;
  int mismatches = 0;
  for (const Ray& ray : randomRays(100'000, 2)) {
    const auto expected = bruteForce(g, ray);
    const auto got = intersectBothWidths(bvh, ray);
    hits += expected ? 1 : 0;
    if (expected.has_value() != got.has_value() ||
        (expected && (expected->prim != got->prim || expected->t != got->t))) {
      ++mismatches;
    }
    if (expected.has_value() != occludedBothWidths(bvh, ray)) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(hits, 5000);  // the comparison covers many hits, not only misses
}

// Trees of 1 to 24 primitives: a root that is one leaf, nodes with fewer
// than kBvhWidth children and empty lanes. Every primitive sits in exactly one
// leaf, every lane in use has a box, unused lanes are empty, and hits equal
// the brute-force loop.
TEST_P(BvhBuilders, SmallTreesHaveWellFormedWideNodes) {
  for (int n = 1; n <= 24; ++n) {
    const Geometry g = randomSoup(n - n / 3, n / 3, static_cast<unsigned>(n));
    BvhSettings settings;
    settings.builder = GetParam();
    const int leafSize = n <= 12 ? 1 : 4;  // leaves of one primitive, then blocks too
    settings.maxLeafSize = leafSize;
    const Bvh bvh = Bvh::build(g, settings);
    for (const BvhNode& node : bvh.nodes()) {
      ASSERT_GE(node.children, 1);
      ASSERT_LE(node.children, kBvhWidth);
      for (int lane = 0; lane < kBvhWidth; ++lane) {
        const Bounds3 box = node.boxes.get(lane);
        EXPECT_EQ(box.empty(), lane >= node.children) << "n " << n << " lane " << lane;
        if (lane < node.children && node.count[lane] == 0) {
          EXPECT_LT(node.offset[lane], bvh.nodes().size());
        }
      }
    }
    expectEachPrimitiveInOneLeaf(g, bvh, leafSize);
    for (const Ray& ray : randomRays(2000, static_cast<unsigned>(100 + n))) {
      const auto expected = bruteForce(g, ray);
      const auto got = intersectBothWidths(bvh, ray);
      ASSERT_EQ(expected.has_value(), got.has_value()) << "n " << n;
      if (expected) {
        EXPECT_EQ(expected->prim, got->prim);
      }
      EXPECT_EQ(expected.has_value(), occludedBothWidths(bvh, ray));
    }
  }
}

// The grid mesh shot at with axis-parallel and random rays: its small
// triangles go into block leaves, tested four lanes at once, and every hit
// has the bits of the brute-force loop's scalar tests.
TEST_P(BvhBuilders, GridMeshOnNodeFacesEqualsBruteForce) {
  constexpr int kN = 8;
  const Geometry g = gridMesh();
  BvhSettings settings;
  settings.builder = GetParam();
  const Bvh bvh = Bvh::build(g, settings);
  EXPECT_GT(expectEachPrimitiveInOneLeaf(g, bvh, settings.maxLeafSize), 8);
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> cell(-4, 4 * kN + 4);
  std::normal_distribution<float> dir;
  int mismatches = 0;
  int hits = 0;
  for (int i = 0; i < 1'000'000; ++i) {
    const glm::vec3 o(cell(rng) * 0.0625f, 2.0f, cell(rng) * 0.0625f);
    glm::vec3 d(0.0f, -1.0f, 0.0f);
    if (i % 2 == 1) d = glm::normalize(glm::vec3(dir(rng), -std::abs(dir(rng)) - 0.1f, dir(rng)));
    const Ray ray(o, d);
    const auto expected = bruteForce(g, ray);
    const auto got = intersectBothWidths(bvh, ray);
    hits += expected ? 1 : 0;
    if (expected.has_value() != got.has_value() || (expected && std::memcmp(&*expected, &*got, sizeof(Hit)) != 0)) {
      ++mismatches;
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(hits, 300'000);
}

INSTANTIATE_TEST_SUITE_P(Builders, BvhBuilders, ::testing::Values(BvhBuilder::kQSplit, BvhBuilder::kSah),
                         [](const auto& info) {
                           return info.param == BvhBuilder::kSah ? std::string("Sah") : std::string("QSplit");
                         });

// Subtrees built on threads of their own give the tree one thread builds:
// the same nodes, byte for byte, the same primitive order and the same
// blocks (filled on a thread of their own).
TEST_P(BvhBuilders, ParallelBuildEqualsSerialBuild) {
  const Geometry g = randomSoup(60000, 500, 11);
  BvhSettings settings;
  settings.builder = GetParam();
  settings.buildThreads = 1;
  const Bvh serial = Bvh::build(g, settings);
  for (const int threads : {2, 4, 8}) {
    settings.buildThreads = threads;
    const Bvh parallel = Bvh::build(g, settings);
    ASSERT_EQ(parallel.nodes().size(), serial.nodes().size()) << threads;
    EXPECT_EQ(std::memcmp(parallel.nodes().data(), serial.nodes().data(), serial.nodes().size() * sizeof(BvhNode)), 0)
        << threads;
    EXPECT_EQ(parallel.primIds(), serial.primIds()) << threads;
    ASSERT_EQ(parallel.blocks().size(), serial.blocks().size()) << threads;
    const std::size_t blockBytes = serial.blocks().size() * sizeof(TriangleBlock);
    EXPECT_EQ(std::memcmp(parallel.blocks().data(), serial.blocks().data(), blockBytes), 0) << threads;
    EXPECT_EQ(parallel.depth(), serial.depth()) << threads;
  }
}

// The SAH prices triangles by the blocks they fill (Embree's blocked SAH),
// so its splits leave full blocks: the 8 x 8 grid's 128 triangles in 16
// blocks of eight, where pricing each triangle alone split most fours into
// two blocks of two.
TEST(Bvh, SahFillsTheBlocks) {
  const Geometry g = gridMesh();
  const BvhSettings settings;
  const Bvh bvh = Bvh::build(g, settings);
  const int full = static_cast<int>(g.primitiveCount()) / kBlockTriangles;
  EXPECT_EQ(expectEachPrimitiveInOneLeaf(g, bvh, settings.maxLeafSize), full);
  EXPECT_EQ(bvh.blocks().size(), static_cast<std::size_t>(full));
}

// A scene whose root splits off a small part (a floor of two triangles as
// wide as the scene, as in scenes/bunny.json) forks below the root: the
// same tree as one thread builds.
TEST(Bvh, ForkBelowTheRootEqualsSerialBuild) {
  Geometry g = randomSoup(6000, 0, 5);
  MeshInput floor;
  floor.positions = {{-1000, -20, -1000}, {1000, -20, -1000}, {1000, -20, 1000}, {-1000, -20, 1000}};
  floor.indices = {0, 1, 2, 0, 2, 3};
  g.addMesh(std::move(floor));
  BvhSettings settings;
  settings.buildThreads = 1;
  const Bvh serial = Bvh::build(g, settings);
  settings.buildThreads = 2;
  const Bvh parallel = Bvh::build(g, settings);
  ASSERT_EQ(parallel.nodes().size(), serial.nodes().size());
  EXPECT_EQ(std::memcmp(parallel.nodes().data(), serial.nodes().data(), serial.nodes().size() * sizeof(BvhNode)), 0);
  EXPECT_EQ(parallel.primIds(), serial.primIds());
}

TEST(Bvh, EmptyTreeFindsNothing) {
  const Geometry g;
  const Bvh bvh = Bvh::build(g, {});
  EXPECT_FALSE(bvh.intersect(Ray({0, 0, 0}, {0, 0, 1}), 1e30f));
  EXPECT_FALSE(bvh.occluded(Ray({0, 0, 0}, {0, 0, 1}), 1e30f));
}

TEST(Bvh, IdenticalPrimitivesStayWithinTheStackDepth) {
  Geometry g;
  for (int i = 0; i < 5000; ++i) g.addSphere({{0, 0, 0}, 1.0f, 0});
  for (BvhBuilder builder : {BvhBuilder::kQSplit, BvhBuilder::kSah}) {
    BvhSettings settings;
    settings.builder = builder;
    const Bvh bvh = Bvh::build(g, settings);
    EXPECT_LE(bvh.depth(), kBvhMaxDepth);
    EXPECT_TRUE(bvh.intersect(Ray({0, 0, 5}, {0, 0, -1}), 1e30f));
  }
}

TEST(Bvh, DegenerateTrianglesAreDroppedAndCounted) {
  Geometry g;
  MeshInput mesh;
  const float nan = std::nanf("");
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {nan, 0, 0}};
  mesh.indices = {0, 1, 2,   // good
                  0, 1, 3,   // collinear
                  0, 0, 2,   // repeated vertex
                  0, 1, 4};  // NaN vertex
  g.addMesh(std::move(mesh));
  EXPECT_EQ(g.triangles().size(), 1u);
  EXPECT_EQ(g.droppedTriangles(), 3u);
  const Bvh bvh = Bvh::build(g, {});
  const auto hit = bvh.intersect(Ray({0.2f, 0.2f, 1.0f}, {0, 0, -1}), 1e30f);
  ASSERT_TRUE(hit);
  EXPECT_FLOAT_EQ(hit->t, 1.0f);
}

}  // namespace
}  // namespace glint
