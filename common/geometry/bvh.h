#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "common/geometry/bounds.h"
#include "common/geometry/geometry.h"
#include "common/base/enum_words.h"
#include "common/geometry/ray.h"
#include "common/geometry/triangle_lanes.h"
#include "common/geometry/wide_slab.h"

namespace glint {

enum class BvhBuilder {
  kQSplit,  // the thesis's: midpoint of the node's box, axis cycling x, y, z per level
  kSah,     // binned surface area heuristic (Wald 2007)
};

template <>
struct EnumWords<BvhBuilder> {
  static constexpr std::array<std::pair<BvhBuilder, std::string_view>, 2> kWords{
      {{BvhBuilder::kSah, "sah"}, {BvhBuilder::kQSplit, "qsplit"}}};
};

// Every tuning knob of the BVH build, with its default.
struct BvhSettings {
  BvhBuilder builder = BvhBuilder::kSah;
  int maxLeafSize = kBlockTriangles;  // a node with at most this many primitives may become a leaf
  int sahBins = 16;        // the most centroid bins per axis for the SAH (a node of n primitives: 4 + n / 20)
  float traversalCost = 1.0f;  // SAH cost of visiting a node, relative to one primitive test
  // Threads the build may use (0: the compute pool's, common/base/compute_pool.h):
  // large subtrees near the root are built side by side. The tree is the same for any count.
  int buildThreads = 0;
};

// One node of the 8-wide tree that traversal walks, 256 bytes. The builder
// makes a binary tree (QSplit or SAH) and collapses it: each node takes up to
// kBvhWidth of the binary tree's nodes below it as children, so that one
// slab test of eight boxes replaces up to three levels of binary box tests;
// a child that is a leaf of two to kBlockTriangles triangles, or a subtree
// of at most that many that the SAH prices cheaper as one leaf, becomes a
// block leaf (TriangleBlock).
//   bytes   0-191  the children's boxes, structure of arrays (WideBoxes)
//   bytes 192-223  offset per child: an interior child's node index, or a
//                  leaf child's first entry in Bvh::primIds
//   bytes 224-239  count per child: a leaf child's primitives (>= 1), 0 for
//                  an interior child; with kBlockLeaf set, the leaf is a
//                  TriangleBlock and its offset an index in Bvh::blocks
//   byte  240      children in use (1 to 8; unused lanes hold empty boxes)
//   bytes 241-255  padding
// The root is node 0.
struct BvhNode {
  WideBoxes boxes;
  std::array<std::uint32_t, kBvhWidth> offset;
  std::array<std::uint16_t, kBvhWidth> count;
  std::uint8_t children;
};
static_assert(kBvhWidth == 8 && sizeof(BvhNode) == 256, "BvhNode is documented as 8 children in 256 bytes");

// How many of a node's boxes the traversal tests in one instruction: eight
// where the CPU has AVX2, else four (SSE, NEON), a node in two halves. The
// same bits either way; the default is the fastest this CPU has.
enum class BoxTestWidth { kFour, kEight };
inline BoxTestWidth fastestBoxTestWidth() {
#if defined(__x86_64__)
  if (avx2Available()) return BoxTestWidth::kEight;
#endif
  return BoxTestWidth::kFour;
}

// A leaf of two to kBlockTriangles triangles tested together: their
// vertices side by side and their primitive ids, lanes from the leaf's count
// on unused. 320 bytes. Traversal tests a block of up to four in four lanes,
// a larger one in eight (with AVX2) or twice four.
struct TriangleBlock {
  TriangleLanes vertices;
  std::array<std::uint32_t, kBlockTriangles> prims;
};

// The bit of BvhNode::count that marks a block leaf (counts are at most 255).
constexpr std::uint16_t kBlockLeaf = 0x8000;

// The builder's binary tree is at most this deep (a depth guard switches to
// median splits before it could grow deeper); traversal sizes its stack by it.
constexpr int kBvhMaxDepth = 64;

// A BVH over one Geometry, bound to it: its primitive ids mean nothing for
// another, so the queries take only the ray. The geometry must outlive it and
// stay where it is (PreparedScene keeps the two together).
// What a builder makes (common/geometry/bvh_build.cpp and bvh_collapse.h) and hands
// to the Bvh it builds, finished.
struct BvhArrays {
  std::vector<BvhNode> nodes;
  std::vector<std::uint32_t> primIds;
  std::unique_ptr<TriangleBlock[]> blocks;
  std::size_t blockCount = 0;
  int depth = 0;
};

class Bvh {
 public:
  Bvh() = default;  // empty: finds nothing
  static Bvh build(const Geometry& geometry, const BvhSettings& settings);

  // Nearest hit with t < tMax; boxes are skipped once they lie beyond the
  // nearest hit so far.
  std::optional<Hit> intersect(const Ray& ray, float tMax) const {
    return intersect(ray, tMax, fastestBoxTestWidth());
  }
  // Any hit with t < tMax (shadow rays): stops at the first one.
  bool occluded(const Ray& ray, float tMax) const { return occluded(ray, tMax, fastestBoxTestWidth()); }
  // The same with a chosen box test (kEight runs as kFour where the CPU
  // lacks AVX2): tests compare the two.
  std::optional<Hit> intersect(const Ray& ray, float tMax, BoxTestWidth width) const;
  bool occluded(const Ray& ray, float tMax, BoxTestWidth width) const;

  const std::vector<BvhNode>& nodes() const { return arrays_.nodes; }
  // Every primitive once, each leaf's a range (a block leaf's too, though
  // traversal reads its ids from the block).
  const std::vector<std::uint32_t>& primIds() const { return arrays_.primIds; }
  std::span<const TriangleBlock> blocks() const { return {arrays_.blocks.get(), arrays_.blockCount}; }
  // Levels of the binary tree the builder made (at most kBvhMaxDepth).
  int depth() const { return arrays_.depth; }

 private:
  Bvh(const Geometry& geometry, BvhArrays arrays) : geometry_(&geometry), arrays_(std::move(arrays)) {}
  // The queries with V (Float4 or Float8) lanes per box test instruction.
  template <typename V>
  std::optional<Hit> nearestHit(const Ray& ray, float tMax) const;
  template <typename V>
  bool anyHit(const Ray& ray, float tMax) const;
  std::optional<Hit> nearestHitFour(const Ray& ray, float tMax) const;
  bool anyHitFour(const Ray& ray, float tMax) const;
  std::optional<Hit> nearestHitEight(const Ray& ray, float tMax) const;
  bool anyHitEight(const Ray& ray, float tMax) const;
  const Geometry* geometry_ = nullptr;
  BvhArrays arrays_;
};

}  // namespace glint
