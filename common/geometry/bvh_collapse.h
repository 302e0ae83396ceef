#pragma once

// The builder's second step (bvh_build.cpp makes the binary tree, this makes
// the tree traversal walks): the binary tree collapsed into 8-wide nodes,
// small groups of triangles into block leaves, as the cost pass
// (bvh_lanes.h) places them.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>

#include <glm/vec3.hpp>

#include "common/geometry/bounds.h"
#include "common/geometry/bvh.h"

namespace glint {

class BvhLanePlan;

// A node of the binary tree the splits make, before it is collapsed into the
// 8-wide nodes that traversal walks. Trivial, so that the builder's array of
// them costs nothing until written. Nodes are depth-first: an interior
// node's first child is the next node, and a subtree's primitives are one
// range of Bvh::primIds.
struct BinaryNode {
  glm::vec3 min;  // the node's box (GLM's vectors are trivial too)
  glm::vec3 max;
  std::uint32_t offset;  // leaf: first entry in primIds; interior: the second child
  std::uint32_t count;   // leaf: primitives; interior: 0 (the first child is the next node)

  Bounds3 bounds() const { return {min, max}; }
};
static_assert(std::is_trivially_default_constructible_v<BinaryNode> && sizeof(BinaryNode) == 32);

// A block leaf's primitives while the collapse has chosen it and the filler
// not yet written it: a range of Bvh::primIds.
struct BlockRange {
  std::uint32_t first;
  std::uint32_t count;
};

// Fills the nodes and blocks of `out` from the binary tree rooted at
// binary[0], whose leaves index out.primIds (already written).
class BvhCollapse {
 public:
  // leafCapacity: the most primitives a leaf may hold (a block, at most
  // kBlockTriangles); twoThreads: whether the blocks may be filled on a
  // second thread.
  BvhCollapse(BvhArrays& out, const Geometry& geometry, const BinaryNode* binary, std::size_t leafCapacity,
              bool twoThreads)
      : out_(out), geometry_(geometry), binary_(binary), leafCapacity_(leafCapacity), twoThreads_(twoThreads) {}

  // Collapses the tree over primCount primitives and fills its blocks.
  void run(std::size_t primCount);

 private:
  std::uint32_t collapse(std::uint32_t index, const BvhLanePlan& plan);
  BlockRange rangeOf(std::uint32_t index) const;
  std::uint32_t addBlock(BlockRange range);
  void fillBlocks(std::size_t begin, std::size_t end);

  BvhArrays& out_;
  const Geometry& geometry_;
  const BinaryNode* binary_;
  std::size_t leafCapacity_;
  bool twoThreads_;
  // The block leaves made so far, by index (blocksMade_ of them, published
  // to the filler thread).
  std::unique_ptr<BlockRange[]> blockRanges_;
  std::atomic<std::size_t> blocksMade_{0};
  std::atomic<bool> collapsed_{false};
};

}  // namespace glint
