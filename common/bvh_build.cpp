#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <optional>
#include <span>

#include "common/bvh.h"

namespace glint {

// Builds the flat tree depth-first: a node is appended, its first child
// follows it, and the second child's index is patched in afterwards.
class BvhBuilderImpl {
 public:
  BvhBuilderImpl(Bvh& bvh, const BvhSettings& settings) : bvh_(bvh), settings_(settings) {}

  void build(std::span<BuildPrimitive> prims, int depth) {
    bvh_.depth_ = std::max(bvh_.depth_, depth + 1);
    const auto nodeIndex = static_cast<std::uint32_t>(bvh_.nodes_.size());
    bvh_.nodes_.push_back({});
    Bounds3 bounds;
    Bounds3 centroids;
    for (const BuildPrimitive& p : prims) {
      bounds.expand(p.bounds);
      centroids.expand(p.bounds.centre());
    }
    bvh_.nodes_[nodeIndex].bounds = bounds;

    const auto count = static_cast<int>(prims.size());
    std::size_t mid = 0;
    int axis = 0;
    if (count > 1) mid = chooseSplit(prims, bounds, centroids, depth, &axis);
    if (mid == 0) {
      makeLeaf(nodeIndex, prims);
      return;
    }
    build(prims.first(mid), depth + 1);
    const auto second = static_cast<std::uint32_t>(bvh_.nodes_.size());
    build(prims.subspan(mid), depth + 1);
    BvhNode& node = bvh_.nodes_[nodeIndex];
    node.offset = second;
    node.count = 0;
    node.axis = static_cast<std::uint8_t>(axis);
  }

 private:
  void makeLeaf(std::uint32_t nodeIndex, std::span<BuildPrimitive> prims) {
    BvhNode& node = bvh_.nodes_[nodeIndex];
    node.offset = static_cast<std::uint32_t>(bvh_.primIds_.size());
    node.count = static_cast<std::uint16_t>(prims.size());
    for (const BuildPrimitive& p : prims) bvh_.primIds_.push_back(p.id);
  }

  // Returns the size of the first half after partitioning prims (0: leaf).
  std::size_t chooseSplit(std::span<BuildPrimitive> prims, const Bounds3& bounds,
                          const Bounds3& centroids, int depth, int* axis) {
    const std::size_t n = prims.size();
    const bool fitsLeaf = n <= leafCapacity();
    // Depth guard: a count-median split from here on always fits the
    // traversal stack, so switch to it before the tree could grow too deep.
    const int levelsLeft = kBvhMaxDepth - 1 - depth;
    if (static_cast<int>(std::bit_width(n)) < levelsLeft) {
      const std::optional<std::size_t> mid = settings_.builder == BvhBuilder::kQSplit
                                                 ? qsplit(prims, bounds, depth, axis)
                                                 : sah(prims, bounds, centroids, axis);
      if (!mid) return 0;
      if (*mid > 0 && *mid < n) return *mid;
    }
    if (fitsLeaf) return 0;
    // Median by centroid along the longest centroid axis: always halves, also
    // where every centroid is the same point.
    const int a = centroids.longestAxis();
    *axis = a;
    const std::size_t half = n / 2;
    std::nth_element(prims.begin(), prims.begin() + static_cast<std::ptrdiff_t>(half), prims.end(),
                     [a](const BuildPrimitive& x, const BuildPrimitive& y) {
                       return x.bounds.centre()[a] < y.bounds.centre()[a];
                     });
    return half;
  }

  std::size_t leafCapacity() const {
    return static_cast<std::size_t>(std::clamp(settings_.maxLeafSize, 1, kMaxLeafPrims));
  }

  // Mansfield's QSplit, as the thesis builds it: split the primitives around
  // the middle of the node's box along the axis of this level (x, y, z, x...).
  // Returns nullopt for a leaf, else the partition point (0 or n when every
  // centroid fell on one side).
  std::optional<std::size_t> qsplit(std::span<BuildPrimitive> prims, const Bounds3& bounds,
                                    int depth, int* axis) {
    if (prims.size() <= leafCapacity()) return std::nullopt;
    const int a = depth % 3;
    *axis = a;
    const float middle = bounds.centre()[a];
    const auto it = std::partition(prims.begin(), prims.end(), [a, middle](const BuildPrimitive& p) {
      return p.bounds.centre()[a] < middle;
    });
    return static_cast<std::size_t>(it - prims.begin());
  }

  // Binned SAH: sahBins buckets of centroids per axis, the cheapest plane of
  // all three axes; returns nullopt when a leaf is cheaper than any split.
  std::optional<std::size_t> sah(std::span<BuildPrimitive> prims, const Bounds3& bounds, const Bounds3& centroids,
                  int* axis) {
    const int bins = std::clamp(settings_.sahBins, 2, kMaxBins);
    float bestCost = std::numeric_limits<float>::infinity();
    int bestAxis = -1;
    int bestPlane = 0;
    for (int a = 0; a < 3; ++a) {
      const float lo = centroids.min[a];
      const float extent = centroids.max[a] - lo;
      if (!(extent > 0.0f)) continue;
      std::array<Bounds3, kMaxBins> binBounds{};
      std::array<int, kMaxBins> binCounts{};
      for (const BuildPrimitive& p : prims) {
        const int b = binOf(p.bounds.centre()[a], lo, extent, bins);
        ++binCounts[b];
        binBounds[b].expand(p.bounds);
      }
      // Sweep from the right to get the area and count right of each plane.
      std::array<float, kMaxBins> rightArea{};
      std::array<int, kMaxBins> rightCount{};
      Bounds3 acc;
      int cnt = 0;
      for (int b = bins - 1; b > 0; --b) {
        acc.expand(binBounds[b]);
        cnt += binCounts[b];
        rightArea[b] = acc.surfaceArea();
        rightCount[b] = cnt;
      }
      acc = Bounds3{};
      cnt = 0;
      for (int plane = 1; plane < bins; ++plane) {
        acc.expand(binBounds[plane - 1]);
        cnt += binCounts[plane - 1];
        if (cnt == 0 || rightCount[plane] == 0) continue;
        const float cost = acc.surfaceArea() * cnt + rightArea[plane] * rightCount[plane];
        if (cost < bestCost) {
          bestCost = cost;
          bestAxis = a;
          bestPlane = plane;
        }
      }
    }
    if (bestAxis < 0) return prims.size() <= leafCapacity() ? std::nullopt : std::optional<std::size_t>(0);
    const float area = bounds.surfaceArea();
    const float splitCost = settings_.traversalCost + (area > 0.0f ? bestCost / area : 0.0f);
    const auto leafCost = static_cast<float>(prims.size());
    if (prims.size() <= leafCapacity() && leafCost <= splitCost) return std::nullopt;
    *axis = bestAxis;
    const float lo = centroids.min[bestAxis];
    const float extent = centroids.max[bestAxis] - lo;
    const auto it = std::partition(prims.begin(), prims.end(), [&](const BuildPrimitive& p) {
      return binOf(p.bounds.centre()[bestAxis], lo, extent, bins) < bestPlane;
    });
    return static_cast<std::size_t>(it - prims.begin());
  }

  static int binOf(float c, float lo, float extent, int bins) {
    const int b = static_cast<int>(static_cast<float>(bins) * ((c - lo) / extent));
    return std::clamp(b, 0, bins - 1);
  }

  static constexpr int kMaxBins = 64;
  static constexpr int kMaxLeafPrims = 255;  // BvhNode::count must hold it

  Bvh& bvh_;
  const BvhSettings& settings_;
};

Bvh Bvh::build(std::vector<BuildPrimitive> prims, const BvhSettings& settings) {
  Bvh bvh;
  if (prims.empty()) return bvh;  // traversal of an empty tree finds nothing
  bvh.nodes_.reserve(2 * prims.size() / std::max(1, settings.maxLeafSize) + 1);
  bvh.primIds_.reserve(prims.size());
  BvhBuilderImpl(bvh, settings).build(prims, 0);
  return bvh;
}

Bvh Bvh::build(const Geometry& geometry, const BvhSettings& settings) {
  std::vector<BuildPrimitive> prims;
  prims.reserve(geometry.primitiveCount());
  for (std::uint32_t i = 0; i < geometry.primitiveCount(); ++i) {
    prims.push_back({geometry.primitiveBounds(i), i});
  }
  return build(std::move(prims), settings);
}

}  // namespace glint
