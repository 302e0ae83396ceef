#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "common/base/compute_pool.h"
#include "common/geometry/bvh.h"
#include "common/geometry/bvh_collapse.h"
#include "common/geometry/bvh_split.h"

namespace glint {
namespace {

// Where a split writes its nodes: the next free one in its range, and the
// deepest level it reached.
struct Cursor {
  std::uint32_t next = 0;
  int depth = 0;
};

// Where both halves of a split have at least this many primitives, the
// first such split on each path down the tree (up to log2 of the build
// threads of them) forks its second half onto the compute pool, the first
// on the caller's: the same splits, and the same 8-wide tree as one thread
// builds. The first such split, not only the root's: the bunny scene's root
// splits off its floor, and its bunny forks a level down (a higher limit
// kept the bunny on one thread; docs/performance.md).
constexpr std::size_t kParallelSubtree = 1024;

// The SAH cost of a block leaf's two to kBlockTriangles triangles tested
// together, relative to one node's box test or one primitive's test
// (measured on the 1M-triangle terrain for blocks of four, and again for
// blocks of eight: 1.0 to 2.5 within the noise, docs/performance.md). The
// builder prices leaves of triangles with it; the collapse prices the
// blocks it makes by their count (bvh_collapse.cpp).
constexpr float kBlockTestCost = 1.5f;

}  // namespace

// Builds the binary tree depth-first (a node is appended, its first child
// follows it, and the second child's index is patched in afterwards), large
// subtrees near the root forked onto the compute pool, then collapses it into
// 8-wide nodes.
class BvhBuilderImpl {
 public:
  BvhBuilderImpl(BvhArrays& out, const Geometry& geometry, const BvhSettings& settings)
      : out_(out), geometry_(geometry), settings_(settings) {
    const unsigned threads = static_cast<unsigned>(settings.buildThreads > 0 ? settings.buildThreads
                                                                              : computePool().size());
    forkLevels_ = static_cast<int>(std::bit_width(threads)) - 1;
  }

  void build(std::span<BuildPrimitive> prims) {
    // The binary tree, its nodes depth-first, each subtree's in a range of
    // its own: a subtree over n primitives has at most 2 n - 1 nodes, so a
    // subtree built on another thread starts where its sibling's range ends
    // and both write in place. (The nodes between two such ranges are never
    // read: the collapse follows the links, and the 8-wide tree is the one
    // a single thread makes.)
    const auto tree = std::make_unique_for_overwrite<BinaryNode[]>(2 * prims.size());
    binary_ = tree.get();
    first_ = prims.data();
    Cursor cursor;
    split(prims, NodeBox::of(prims), 0, forkLevels_, cursor);
    // Leaves were made in place: a leaf's primitives are its range of the
    // partitioned array.
    out_.primIds.reserve(prims.size());
    for (const BuildPrimitive& p : prims) out_.primIds.push_back(p.id());
    out_.depth = cursor.depth;
    out_.nodes.reserve(cursor.next / 3 + 1);
    BvhCollapse(out_, geometry_, binary_, leafCapacity(), forkLevels_ > 0).run(prims.size());
  }

 private:
  // forks: how many more times this path down the tree may hand a subtree
  // to a thread of its own (threads at once: at most 2^forkLevels_).
  void split(std::span<BuildPrimitive> prims, const NodeBox& box, int depth, int forks, Cursor& cursor) {
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
    if (forks > 0 && prims.size() - mid >= kParallelSubtree && mid >= kParallelSubtree) {
      Cursor second{nodeIndex + 2 * static_cast<std::uint32_t>(mid), 0};  // after the first half's 2 mid - 1
      ThreadPool::Forked worker =
          computePool().fork([&] { split(prims.subspan(mid), cut.sides[1], depth + 1, forks - 1, second); });
      split(prims.first(mid), cut.sides[0], depth + 1, forks - 1, cursor);
      worker.join();
      node.offset = nodeIndex + 2 * static_cast<std::uint32_t>(mid);
      cursor = {second.next, std::max(cursor.depth, second.depth)};
      return;
    }
    split(prims.first(mid), cut.sides[0], depth + 1, forks, cursor);
    node.offset = cursor.next;
    split(prims.subspan(mid), cut.sides[1], depth + 1, forks, cursor);
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
      const bool qsplitBuild = settings_.builder == BvhBuilder::kQSplit;
      const std::optional<Cut> cut = qsplitBuild ? qsplit(prims, box.bounds.bounds(), depth) : sah(prims, box);
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

  // Binned SAH: buckets of centroids per axis (binsFor), the cheapest plane
  // of all three axes; returns nullopt when a leaf is cheaper than any split.
  std::optional<Cut> sah(std::span<BuildPrimitive> prims, const NodeBox& box) {
    const BinGrid grid(box.centroids, binsFor(prims.size()));
    SahBins bins;  // uninitialised: only the bins in use are emptied
    bins.reset(grid.bins);
    bins.add(prims, grid);
    const bool blocks = box.blocksOnly() && prims.size() >= static_cast<std::size_t>(kBlockPricedFrom);
    const auto price = [blocks](int count) { return leafPrice(count, blocks); };
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
      Box4 acc = Box4::empty();
      int cnt = 0;
      float area = 0.0f;
      for (int b = grid.bins - 1; b > 0; --b) {
        if (bins.counts[a][b] > 0) {
          acc.expand(bins.bounds[a][b]);
          cnt += bins.counts[a][b];
          area = acc.surfaceArea();
        }
        rightArea[b] = area;
        rightCount[b] = cnt;
      }
      acc = Box4::empty();
      cnt = 0;
      for (int plane = 1; plane < grid.bins; ++plane) {
        if (bins.counts[a][plane - 1] == 0) continue;
        acc.expand(bins.bounds[a][plane - 1]);
        cnt += bins.counts[a][plane - 1];
        if (rightCount[plane] == 0) continue;
        const float cost = acc.surfaceArea() * price(cnt) + rightArea[plane] * price(rightCount[plane]);
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
    const float leafCost = price(static_cast<int>(prims.size()));
    if (prims.size() <= leafCapacity() && leafCost <= splitCost) return std::nullopt;
    Cut cut;
    cut.mid = partitionMeasured(
        prims, [&](const BuildPrimitive& p) { return grid.binOf(p)[bestAxis] < bestPlane; }, cut.sides);
    return cut;
  }

  // The SAH's price of a leaf of `count` primitives, in primitive tests:
  // one each, or with `blocks` one block test per kBlockTriangles of them,
  // as Embree's SAH counts blocks, so that splits leave full blocks. sah()
  // prices blocks where a node holds only triangles, at least
  // kBlockPricedFrom: a smaller node priced so is always a leaf, which put
  // the bunny scene's floor (two triangles as wide as the scene) in one
  // block with a bunny triangle, its flat box grown so that every ray
  // leaving the floor entered it; and from eight on (a block's worth), the
  // room's walls split into more blocks, each ray testing more of them
  // (docs/performance.md). 1M terrain triangles: 7.5 triangles a block on
  // average and 37,944 nodes (blocks of four: 3.8 and 72,411; triangles
  // priced alone: 2.5 and 89,931).
  static constexpr int kBlockPricedFrom = 4;
  static float leafPrice(int count, bool blocks) {
    if (!blocks) return static_cast<float>(count);
    return kBlockTestCost * static_cast<float>((count + kBlockTriangles - 1) / kBlockTriangles);
  }

  // Bins per axis for a node of n primitives: 4 + n / 20, at most sahBins,
  // as Embree's BinMapping chooses them: most nodes are small, and 16 bins
  // for a handful of primitives cost more than they found: a faster build,
  // traversal as fast (docs/performance.md).
  int binsFor(std::size_t n) const {
    const auto most = static_cast<std::size_t>(std::clamp(settings_.sahBins, 2, kMaxBins));
    return static_cast<int>(std::min(4 + n / 20, most));
  }

  static constexpr int kMaxLeafPrims = 255;  // BvhNode::count must hold it

  BvhArrays& out_;
  const Geometry& geometry_;
  BinaryNode* binary_ = nullptr;            // the tree being built, then collapsed
  const BuildPrimitive* first_ = nullptr;   // the primitives' array, where primIds start
  const BvhSettings& settings_;
  int forkLevels_ = 0;  // forks on a path down the tree: log2 of the build threads
};

Bvh Bvh::build(const Geometry& geometry, const BvhSettings& settings) {
  std::vector<BuildPrimitive> prims;
  prims.reserve(geometry.primitiveCount());
  for (std::uint32_t i = 0; i < geometry.primitiveCount(); ++i) {
    prims.push_back({geometry.primitiveBounds(i), i, geometry.isSphere(i)});
  }
  BvhArrays arrays;
  if (!prims.empty()) BvhBuilderImpl(arrays, geometry, settings).build(prims);  // an empty tree finds nothing
  return Bvh(geometry, std::move(arrays));
}

}  // namespace glint
