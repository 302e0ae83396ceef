#include "common/geometry/bvh_collapse.h"

#include <algorithm>
#include <array>
#include <thread>

#include "common/base/compute_pool.h"
#include "common/geometry/bvh_lanes.h"

namespace glint {
namespace {

// Builds of fewer primitives fill their blocks on the collapse's thread.
constexpr std::size_t kFillerThreadFrom = 4096;

}  // namespace

// Makes the 8-wide node for binary node `index` and, recursively, those
// below it; returns its index. Its children are the binary nodes the cost
// pass chose for its lanes (the node itself where the whole tree is one
// leaf); each becomes a leaf, a block leaf or a node of its own.
std::uint32_t BvhCollapse::collapse(std::uint32_t index, const BvhLanePlan& plan) {
  std::array<std::uint32_t, kBvhWidth> children{};
  const int n = plan.lanesOf(index, children);
  const auto wideIndex = static_cast<std::uint32_t>(out_.nodes.size());
  out_.nodes.emplace_back();
  for (int lane = n; lane < kBvhWidth; ++lane) out_.nodes[wideIndex].boxes.set(lane, Bounds3{});
  out_.nodes[wideIndex].children = static_cast<std::uint8_t>(n);
  for (int lane = 0; lane < n; ++lane) {
    const std::uint32_t child = children[static_cast<std::size_t>(lane)];
    const LaneUse use = plan.use(child);
    std::uint32_t offset = 0;
    std::uint16_t count = 0;
    if (use == LaneUse::kNode) {
      offset = collapse(child, plan);  // appends nodes: index the vector afresh after it
    } else {
      const BlockRange range = rangeOf(child);
      offset = use == LaneUse::kBlock ? addBlock(range) : range.first;
      count = static_cast<std::uint16_t>(range.count | (use == LaneUse::kBlock ? kBlockLeaf : 0u));
    }
    BvhNode& node = out_.nodes[wideIndex];
    node.boxes.set(lane, binary_[child].bounds());
    node.offset[static_cast<std::size_t>(lane)] = offset;
    node.count[static_cast<std::size_t>(lane)] = count;
  }
  return wideIndex;
}

// The primitives of binary node `index`'s subtree: one range of primIds,
// from its first leaf's first to its last leaf's last.
BlockRange BvhCollapse::rangeOf(std::uint32_t index) const {
  std::uint32_t first = index;
  while (binary_[first].count == 0) ++first;
  std::uint32_t last = index;
  while (binary_[last].count == 0) last = binary_[last].offset;
  const std::uint32_t begin = binary_[first].offset;
  return {begin, binary_[last].offset + binary_[last].count - begin};
}

// A block leaf of primIds[range]; the block filler writes it.
std::uint32_t BvhCollapse::addBlock(BlockRange range) {
  const std::size_t index = blocksMade_.load(std::memory_order_relaxed);
  blockRanges_[index] = range;
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
  out_.blocks = std::make_unique_for_overwrite<TriangleBlock[]>(capacity);
  const BvhLanePlan plan(binary_, 2 * primCount,
                         std::min<std::size_t>(kBlockTriangles, leafCapacity_),
                         [this](const BinaryNode& leaf) {
                           for (std::uint32_t i = leaf.offset; i < leaf.offset + leaf.count; ++i) {
                             if (geometry_.isSphere(out_.primIds[i])) return false;
                           }
                           return true;
                         });
  if (!twoThreads_ || primCount < kFillerThreadFrom) {
    collapse(0, plan);
    fillBlocks(0, blocksMade_.load(std::memory_order_relaxed));
  } else {
    // If no worker takes the filler before the collapse ends, join() runs it
    // here, and it fills every block at once.
    ThreadPool::Forked filler = computePool().fork([this] {
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
      collapse(0, plan);
    } catch (...) {  // out of memory: let the filler finish before the error goes on
      collapsed_.store(true, std::memory_order_release);
      try {
        filler.join();
      } catch (...) {  // the collapse's own error is the one to report
      }
      throw;
    }
    collapsed_.store(true, std::memory_order_release);
    filler.join();
  }
  out_.blockCount = blocksMade_.load(std::memory_order_relaxed);
}

// Writes blocks [begin, end): their triangles' vertices copied side by
// side, unused lanes zero.
void BvhCollapse::fillBlocks(std::size_t begin, std::size_t end) {
  const Geometry& g = geometry_;
  for (std::size_t b = begin; b < end; ++b) {
    TriangleBlock block{};
    for (std::uint32_t lane = 0; lane < blockRanges_[b].count; ++lane) {
      const std::uint32_t prim = out_.primIds[blockRanges_[b].first + lane];
      const Triangle& t = g.triangles()[prim];
      block.vertices.set(static_cast<int>(lane), g.positions()[t.v[0]], g.positions()[t.v[1]],
                         g.positions()[t.v[2]]);
      block.prims[lane] = prim;
    }
    out_.blocks[b] = block;
  }
}

}  // namespace glint
