#include "common/bvh_collapse.h"

#include <algorithm>
#include <thread>

namespace glint {
namespace {

// What the collapse weighs, relative to one node's box test
// (measured on the 1M-triangle terrain, docs/performance.md): one triangle
// tested alone (a block's triangles: kBlockTestCost).
constexpr float kNodeTestCost = 1.0f;
constexpr float kTriangleTestCost = 1.0f;

// Builds of fewer primitives fill their blocks on the collapse's thread.
constexpr std::size_t kFillerThreadFrom = 4096;

}  // namespace

// Makes the 8-wide node for binary node `index` and, recursively, those
// below it; returns its index. Its children start as the binary node's two
// (or the node itself when the whole tree is one leaf); while there are
// fewer than kBvhWidth, the interior child with the largest surface area (the
// one most rays enter) is replaced by its own two children. Then each
// child becomes a leaf (see leafOf) or a node of its own.
std::uint32_t BvhCollapse::collapse(std::uint32_t index) {
  std::array<std::uint32_t, kBvhWidth> children{};
  int n = 0;
  if (binary_[index].count > 0) {
    children[n++] = index;
  } else {
    children[n++] = index + 1;
    children[n++] = binary_[index].offset;
  }
  while (n < kBvhWidth) {
    int widest = -1;
    float widestArea = -1.0f;
    for (int i = 0; i < n; ++i) {
      const BinaryNode& c = binary_[children[i]];
      if (c.count > 0) continue;
      const float area = c.bounds().surfaceArea();
      if (area > widestArea) {
        widest = i;
        widestArea = area;
      }
    }
    if (widest < 0) break;
    const std::uint32_t opened = children[widest];
    children[widest] = opened + 1;
    children[n++] = binary_[opened].offset;
  }
  const auto wideIndex = static_cast<std::uint32_t>(bvh_.nodes_.size());
  bvh_.nodes_.emplace_back();
  for (int lane = n; lane < kBvhWidth; ++lane) bvh_.nodes_[wideIndex].boxes.set(lane, Bounds3{});
  bvh_.nodes_[wideIndex].children = static_cast<std::uint8_t>(n);
  for (int lane = 0; lane < n; ++lane) {
    const std::optional<Leaf> leaf = leafOf(children[lane]);
    // The recursion appends nodes: index the vector afresh after it.
    const std::uint32_t offset = leaf ? leaf->offset : collapse(children[lane]);
    BvhNode& node = bvh_.nodes_[wideIndex];
    node.boxes.set(lane, binary_[children[lane]].bounds());
    node.offset[lane] = offset;
    node.count[lane] = static_cast<std::uint16_t>(leaf ? leaf->count | (leaf->block ? kBlockLeaf : 0u) : 0u);
  }
  return wideIndex;
}

// The leaf that binary node `index` becomes in the 8-wide tree, or nullopt
// for a node. A binary leaf of two to kBlockTriangles triangles becomes a
// block. A subtree of at most that many triangles becomes one block leaf
// where that is cheaper, by the surface area heuristic, than a node over its
// leaves.
std::optional<BvhCollapse::Leaf> BvhCollapse::leafOf(std::uint32_t index) {
  SmallSubtree small;
  const bool fits = gather(index, small) && small.triangles;
  const BinaryNode& node = binary_[index];
  if (node.count > 0 && !(fits && node.count > 1)) return Leaf{node.offset, node.count, false};
  if (!fits) return std::nullopt;
  if (node.count == 0) {
    const float area = node.bounds().surfaceArea();
    if (area * kBlockTestCost > area * kNodeTestCost + small.leafCost) return std::nullopt;
  }
  return Leaf{addBlock(small.first, small.count), small.count, true};
}

// Adds binary node `index`'s leaves to `small`; false once it would hold
// more than kBlockTriangles primitives, or more than a leaf may, or lies
// more than three levels deep (as a balanced subtree of eight leaves): a
// larger subtree is told apart without walking it.
bool BvhCollapse::gather(std::uint32_t index, SmallSubtree& small, int level) const {
  const BinaryNode& node = binary_[index];
  if (node.count == 0) {
    return level < 3 && gather(index + 1, small, level + 1) && gather(node.offset, small, level + 1);
  }
  small.count += node.count;
  if (small.count > std::min<std::size_t>(kBlockTriangles, leafCapacity_)) return false;
  small.first = std::min(small.first, node.offset);
  bool triangles = true;
  for (std::uint32_t i = node.offset; i < node.offset + node.count; ++i) {
    triangles = triangles && !bvh_.geometry_->isSphere(bvh_.primIds_[i]);
  }
  small.triangles = small.triangles && triangles;
  const float test = triangles && node.count > 1 ? kBlockTestCost
                                                 : kTriangleTestCost * static_cast<float>(node.count);
  small.leafCost += node.bounds().surfaceArea() * test;
  return true;
}

// A block leaf of primIds[first, first + count); the block filler writes it.
std::uint32_t BvhCollapse::addBlock(std::uint32_t first, std::uint32_t count) {
  const std::size_t index = blocksMade_.load(std::memory_order_relaxed);
  blockRanges_[index] = {first, count};
  blocksMade_.store(index + 1, std::memory_order_release);
  return static_cast<std::uint32_t>(index);
}

// Collapses the binary tree while the blocks it makes are filled: on a
// thread of their own where the build has two or more, as the collapse
// makes them (it runs on one thread, the other would be idle).
void BvhCollapse::run(std::size_t primCount) {
  const std::size_t capacity = primCount / 2 + 1;  // a block holds two primitives or more
  blockRanges_ = std::make_unique_for_overwrite<BlockRange[]>(capacity);
  // Untouched pages cost nothing: only the blocks made are ever written.
  bvh_.blocks_ = std::make_unique_for_overwrite<TriangleBlock[]>(capacity);
  if (!twoThreads_ || primCount < kFillerThreadFrom) {
    collapse(0);
    fillBlocks(0, blocksMade_.load(std::memory_order_relaxed));
  } else {
    std::thread filler([this] {
      std::size_t next = 0;
      for (bool last = false; !last;) {
        last = collapsed_.load(std::memory_order_acquire);
        const std::size_t made = blocksMade_.load(std::memory_order_acquire);
        if (made == next && !last) std::this_thread::yield();
        fillBlocks(next, made);
        next = made;
      }
    });
    try {
      collapse(0);
    } catch (...) {  // out of memory: let the filler finish before the error goes on
      collapsed_.store(true, std::memory_order_release);
      filler.join();
      throw;
    }
    collapsed_.store(true, std::memory_order_release);
    filler.join();
  }
  bvh_.blockCount_ = blocksMade_.load(std::memory_order_relaxed);
}

// Writes blocks [begin, end): their triangles' vertices copied side by
// side, unused lanes zero.
void BvhCollapse::fillBlocks(std::size_t begin, std::size_t end) {
  const Geometry& g = *bvh_.geometry_;
  for (std::size_t b = begin; b < end; ++b) {
    TriangleBlock block{};
    for (std::uint32_t lane = 0; lane < blockRanges_[b].count; ++lane) {
      const std::uint32_t prim = bvh_.primIds_[blockRanges_[b].first + lane];
      const Triangle& t = g.triangles()[prim];
      block.vertices.set(static_cast<int>(lane), g.positions()[t.v[0]], g.positions()[t.v[1]],
                         g.positions()[t.v[2]]);
      block.prims[lane] = prim;
    }
    bvh_.blocks_[b] = block;
  }
}

}  // namespace glint
