#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <thread>
#include <type_traits>
#include <vector>

#include "common/bvh.h"
#include "common/bvh_split.h"

namespace glint {
namespace {

// A node of the binary tree the splits make, before it is collapsed into the
// 4-wide nodes that traversal walks. Trivial, so that the builder's array of
// them costs nothing until written.
struct BinaryNode {
  glm::vec3 min;  // the node's box (GLM's vectors are trivial too)
  glm::vec3 max;
  std::uint32_t offset;  // leaf: first entry in primIds; interior: the second child
  std::uint32_t count;   // leaf: primitives; interior: 0 (the first child is the next node)

  Bounds3 bounds() const { return {min, max}; }
};
static_assert(std::is_trivially_default_constructible_v<BinaryNode> && sizeof(BinaryNode) == 32);

// Where a split writes its nodes: the next free one in its range, and the
// deepest level it reached.
struct Cursor {
  std::uint32_t next = 0;
  int depth = 0;
};

// Subtrees of at least this many primitives near the root are built on a
// thread of their own (the second child's; the first stays on the caller's):
// the same splits, and the same 4-wide tree as one thread builds.
constexpr std::size_t kParallelSubtree = 4096;

}  // namespace

// Builds the binary tree depth-first (a node is appended, its first child
// follows it, and the second child's index is patched in afterwards), large
// subtrees near the root on threads of their own, then collapses it into
// 4-wide nodes.
class BvhBuilderImpl {
 public:
  BvhBuilderImpl(Bvh& bvh, const BvhSettings& settings) : bvh_(bvh), settings_(settings) {
    const unsigned threads = settings.buildThreads > 0 ? static_cast<unsigned>(settings.buildThreads)
                                                       : std::max(1u, std::thread::hardware_concurrency());
    forkLevels_ = static_cast<int>(std::bit_width(threads)) - 1;
  }

  void build(std::span<BuildPrimitive> prims) {
    // The binary tree, its nodes depth-first, each subtree's in a range of
    // its own: a subtree over n primitives has at most 2 n - 1 nodes, so a
    // subtree built on another thread starts where its sibling's range ends
    // and both write in place. (The nodes between two such ranges are never
    // read: the collapse follows the links, and the 4-wide tree is the one
    // a single thread makes.)
    const auto tree = std::make_unique_for_overwrite<BinaryNode[]>(2 * prims.size());
    binary_ = tree.get();
    first_ = prims.data();
    Cursor cursor;
    split(prims, NodeBox::of(prims), 0, cursor);
    // Leaves were made in place: a leaf's primitives are its range of the
    // partitioned array.
    bvh_.primIds_.reserve(prims.size());
    for (const BuildPrimitive& p : prims) bvh_.primIds_.push_back(p.id());
    bvh_.depth_ = cursor.depth;
    bvh_.nodes_.reserve(cursor.next / 3 + 1);
    collapseAndFill(prims.size());
  }

 private:
  void split(std::span<BuildPrimitive> prims, const NodeBox& box, int depth, Cursor& cursor) {
    cursor.depth = std::max(cursor.depth, depth + 1);
    const std::uint32_t nodeIndex = cursor.next++;
    BinaryNode& node = binary_[nodeIndex];
    const Bounds3 bounds = box.bounds.bounds();
    node = {bounds.min, bounds.max, 0, 0};

    Cut cut;
    if (prims.size() > 1) cut = chooseSplit(prims, box, depth);
    const std::size_t mid = cut.mid;
    if (mid == 0) {
      node.offset = static_cast<std::uint32_t>(prims.data() - first_);
      node.count = static_cast<std::uint32_t>(prims.size());
      return;
    }
    if (depth < forkLevels_ && prims.size() - mid >= kParallelSubtree && mid >= kParallelSubtree) {
      Cursor second{nodeIndex + 2 * static_cast<std::uint32_t>(mid), 0};  // after the first half's 2 mid - 1
      std::thread worker([&] { split(prims.subspan(mid), cut.sides[1], depth + 1, second); });
      split(prims.first(mid), cut.sides[0], depth + 1, cursor);
      worker.join();
      node.offset = nodeIndex + 2 * static_cast<std::uint32_t>(mid);
      cursor = {second.next, std::max(cursor.depth, second.depth)};
      return;
    }
    split(prims.first(mid), cut.sides[0], depth + 1, cursor);
    node.offset = cursor.next;
    split(prims.subspan(mid), cut.sides[1], depth + 1, cursor);
  }

  // Makes the 4-wide node for binary node `index` and, recursively, those
  // below it; returns its index. Its children start as the binary node's two
  // (or the node itself when the whole tree is one leaf); while there are
  // fewer than four, the interior child with the largest surface area (the
  // one most rays enter) is replaced by its own two children. Then each
  // child becomes a leaf (see leafOf) or a node of its own.
  std::uint32_t collapse(std::uint32_t index) {
    std::array<std::uint32_t, 4> children{};
    int n = 0;
    if (binary_[index].count > 0) {
      children[n++] = index;
    } else {
      children[n++] = index + 1;
      children[n++] = binary_[index].offset;
    }
    while (n < 4) {
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
    for (int lane = n; lane < 4; ++lane) bvh_.nodes_[wideIndex].boxes.set(lane, Bounds3{});
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

  // What a 4-wide node's lane holds when it is a leaf.
  struct Leaf {
    std::uint32_t offset;  // in primIds, or a block's index
    std::uint32_t count;
    bool block;
  };

  // The leaf that binary node `index` becomes in the 4-wide tree, or nullopt
  // for a node. A binary leaf of two to four triangles becomes a block. A
  // subtree of at most four triangles becomes one block leaf where that is
  // cheaper, by the surface area heuristic, than a node over its leaves.
  std::optional<Leaf> leafOf(std::uint32_t index) {
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

  // The leaves of a subtree of at most four primitives (contiguous in
  // primIds: the leaves were made in place), and the SAH cost of testing
  // them one leaf at a time.
  struct SmallSubtree {
    std::uint32_t first = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t count = 0;
    bool triangles = true;  // no sphere among them
    float leafCost = 0.0f;  // sum over the leaves of area x cost of its test
  };

  // Adds binary node `index`'s leaves to `small`; false once it would hold
  // more than four primitives, or more than a leaf may. (Four leaves lie at most three levels down:
  // a larger subtree is told apart without walking it.)
  bool gather(std::uint32_t index, SmallSubtree& small, int level = 0) const {
    const BinaryNode& node = binary_[index];
    if (node.count == 0) {
      return level < 3 && gather(index + 1, small, level + 1) && gather(node.offset, small, level + 1);
    }
    small.count += node.count;
    if (small.count > std::min<std::size_t>(4, leafCapacity())) return false;
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
  std::uint32_t addBlock(std::uint32_t first, std::uint32_t count) {
    const std::size_t index = blocksMade_.load(std::memory_order_relaxed);
    blockRanges_[index] = {first, count};
    blocksMade_.store(index + 1, std::memory_order_release);
    return static_cast<std::uint32_t>(index);
  }

  // Collapses the binary tree while the blocks it makes are filled: on a
  // thread of their own where the build has two or more, as the collapse
  // makes them (it runs on one thread, the other would be idle).
  void collapseAndFill(std::size_t primCount) {
    const std::size_t capacity = primCount / 2 + 1;  // a block holds two primitives or more
    blockRanges_ = std::make_unique_for_overwrite<BlockRange[]>(capacity);
    // Untouched pages cost nothing: only the blocks made are ever written.
    bvh_.blocks_ = std::make_unique_for_overwrite<TriangleBlock[]>(capacity);
    if (forkLevels_ == 0 || primCount < kParallelSubtree) {
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
  void fillBlocks(std::size_t begin, std::size_t end) {
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

  // Partitions prims for a split and returns where the second half starts
  // with both halves' boxes (mid 0: a leaf).
  Cut chooseSplit(std::span<BuildPrimitive> prims, const NodeBox& box, int depth) {
    const std::size_t n = prims.size();
    const bool fitsLeaf = n <= leafCapacity();
    // Depth guard: a count-median split from here on always fits the
    // traversal stack, so switch to it before the tree could grow too deep.
    const int levelsLeft = kBvhMaxDepth - 1 - depth;
    if (static_cast<int>(std::bit_width(n)) < levelsLeft) {
      const std::optional<Cut> cut = settings_.builder == BvhBuilder::kQSplit ? qsplit(prims, box.bounds.bounds(), depth)
                                                                               : sah(prims, box);
      if (!cut) return {};
      if (cut->mid > 0 && cut->mid < n) return *cut;
    }
    if (fitsLeaf) return {};
    // Median by centroid along the longest centroid axis: always halves, also
    // where every centroid is the same point.
    const int a = box.centroids.bounds().longestAxis();
    const std::size_t half = n / 2;
    std::nth_element(prims.begin(), prims.begin() + static_cast<std::ptrdiff_t>(half), prims.end(),
                     [a](const BuildPrimitive& x, const BuildPrimitive& y) {
                       return x.box.centre()[a] < y.box.centre()[a];
                     });
    return Cut::at(prims, half);
  }

  std::size_t leafCapacity() const {
    return static_cast<std::size_t>(std::clamp(settings_.maxLeafSize, 1, kMaxLeafPrims));
  }

  // Mansfield's QSplit, as the thesis builds it: split the primitives around
  // the middle of the node's box along the axis of this level (x, y, z, x...).
  // Returns nullopt for a leaf, else the partition point (0 or n when every
  // centroid fell on one side).
  std::optional<Cut> qsplit(std::span<BuildPrimitive> prims, const Bounds3& bounds, int depth) {
    if (prims.size() <= leafCapacity()) return std::nullopt;
    const int a = depth % 3;
    const float middle = bounds.centre()[a];
    Cut cut;
    cut.mid = partitionMeasured(
        prims, [a, middle](const BuildPrimitive& p) { return p.box.centre()[a] < middle; }, cut.sides);
    return cut;
  }

  // Binned SAH: sahBins buckets of centroids per axis, the cheapest plane of
  // all three axes; returns nullopt when a leaf is cheaper than any split.
  std::optional<Cut> sah(std::span<BuildPrimitive> prims, const NodeBox& box) {
    const BinGrid grid(box.centroids, std::clamp(settings_.sahBins, 2, kMaxBins));
    SahBins bins;  // uninitialised: only the bins in use are emptied
    bins.reset(grid.bins);
    bins.add(prims, grid);
    float bestCost = std::numeric_limits<float>::infinity();
    int bestAxis = -1;
    int bestPlane = 0;
    for (int a = 0; a < 3; ++a) {
      if (!grid.usable[a]) continue;
      // Sweep from the right to get the area and count right of each plane.
      // An empty bin changes neither box nor count: the plane after it costs
      // what the plane before it did, so it is neither measured nor priced
      // (the first of equal costs wins anyway).
      std::array<float, kMaxBins> rightArea;  // [1, bins) written before read
      std::array<int, kMaxBins> rightCount;
      Bounds3 acc;
      int cnt = 0;
      float area = 0.0f;
      for (int b = grid.bins - 1; b > 0; --b) {
        if (bins.counts[a][b] > 0) {
          acc.expand(bins.bounds[a][b].bounds());
          cnt += bins.counts[a][b];
          area = acc.surfaceArea();
        }
        rightArea[b] = area;
        rightCount[b] = cnt;
      }
      acc = Bounds3{};
      cnt = 0;
      for (int plane = 1; plane < grid.bins; ++plane) {
        if (bins.counts[a][plane - 1] == 0) continue;
        acc.expand(bins.bounds[a][plane - 1].bounds());
        cnt += bins.counts[a][plane - 1];
        if (rightCount[plane] == 0) continue;
        const float cost = acc.surfaceArea() * cnt + rightArea[plane] * rightCount[plane];
        if (cost < bestCost) {
          bestCost = cost;
          bestAxis = a;
          bestPlane = plane;
        }
      }
    }
    if (bestAxis < 0) return prims.size() <= leafCapacity() ? std::nullopt : std::optional<Cut>(Cut{});
    const float area = box.bounds.bounds().surfaceArea();
    const float splitCost = settings_.traversalCost + (area > 0.0f ? bestCost / area : 0.0f);
    const auto leafCost = static_cast<float>(prims.size());
    if (prims.size() <= leafCapacity() && leafCost <= splitCost) return std::nullopt;
    Cut cut;
    cut.mid = partitionMeasured(
        prims, [&](const BuildPrimitive& p) { return grid.binOf(p)[bestAxis] < bestPlane; }, cut.sides);
    return cut;
  }

  static constexpr int kMaxLeafPrims = 255;  // BvhNode::count must hold it
  // What the collapse weighs, relative to one 4-wide node's box test
  // (measured on the 1M-triangle terrain, docs/performance.md): one triangle
  // tested alone, and a block's two to four triangles tested together.
  static constexpr float kNodeTestCost = 1.0f;
  static constexpr float kTriangleTestCost = 1.0f;
  static constexpr float kBlockTestCost = 1.5f;

  Bvh& bvh_;
  BinaryNode* binary_ = nullptr;            // the tree being built, then collapsed
  const BuildPrimitive* first_ = nullptr;   // the primitives' array, where primIds start
  const BvhSettings& settings_;
  int forkLevels_ = 0;  // levels that fork: log2 of the build threads
  struct BlockRange {
    std::uint32_t first;  // in primIds
    std::uint32_t count;
  };
  // The block leaves the collapse made, by index: blocksMade_ of them so
  // far, published to the filler thread.
  std::unique_ptr<BlockRange[]> blockRanges_;
  std::atomic<std::size_t> blocksMade_{0};
  std::atomic<bool> collapsed_{false};
};

Bvh Bvh::build(const Geometry& geometry, const BvhSettings& settings) {
  Bvh bvh;
  bvh.geometry_ = &geometry;
  std::vector<BuildPrimitive> prims;
  prims.reserve(geometry.primitiveCount());
  for (std::uint32_t i = 0; i < geometry.primitiveCount(); ++i) {
    prims.push_back({geometry.primitiveBounds(i), i});
  }
  if (prims.empty()) return bvh;  // traversal of an empty tree finds nothing
  BvhBuilderImpl(bvh, settings).build(prims);
  return bvh;
}

}  // namespace glint
