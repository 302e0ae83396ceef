#include "common/geometry/bvh_lanes.h"

#include <algorithm>

namespace glint {

BvhLanePlan::BvhLanePlan(const BinaryNode* binary, std::size_t capacity, std::size_t blockLimit,
                         const TrianglesOnly& trianglesOnly)
    : binary_(binary),
      blockLimit_(blockLimit),
      choices_(std::make_unique_for_overwrite<Choice[]>(capacity)) {
  const Placement root = choose(0, trianglesOnly);
  // The root is a node whatever its subtree would be in a lane: of its
  // split, or of the one leaf that is the whole tree.
  const double area = binary_[0].bounds().surfaceArea();
  cost_ = binary_[0].count > 0 ? area * kNodeTestCost + root.cost[0] : root.asNode;
}

// For binary node `index` and each k up to kBvhWidth, the cheapest way to
// place its subtree in at most k lanes: in one lane (as a leaf, a block
// leaf, or a node of its own whose lanes are chosen alike), or its two
// children's subtrees in lanes that add up to k. Records the choices;
// returns the costs. Recursive: the tree is at most kBvhMaxDepth deep.
BvhLanePlan::Placement BvhLanePlan::choose(std::uint32_t index,
                                           const TrianglesOnly& trianglesOnly) {
  const BinaryNode& node = binary_[index];
  Choice& choice = choices_[index];
  choice.split.fill(0);
  choice.nodeSplit = 0;
  const double area = node.bounds().surfaceArea();
  Placement p;
  if (node.count > 0) {
    p.count = node.count;
    p.triangles = trianglesOnly(node);
    const bool block = p.triangles && node.count > 1 && node.count <= blockLimit_;
    choice.use = block ? LaneUse::kBlock : LaneUse::kLeaf;
    p.cost.fill(area * (block ? blockTestCost(node.count) : kTriangleTestCost * node.count));
    p.asNode = 0.0;
    return p;
  }
  const Placement first = choose(index + 1, trianglesOnly);
  const Placement second = choose(node.offset, trianglesOnly);
  p.count = first.count + second.count;
  p.triangles = first.triangles && second.triangles;
  // both[k - 1]: the cheapest split of k lanes between the two children's
  // subtrees (choice.split[k - 1] the first child's share).
  std::array<double, kBvhWidth> both{};
  for (std::size_t k = 2; k <= kBvhWidth; ++k) {
    for (std::size_t i = 1; i < k; ++i) {
      const double cost = first.cost[i - 1] + second.cost[k - i - 1];
      if (i == 1 || cost < both[k - 1]) {
        both[k - 1] = cost;
        choice.split[k - 1] = static_cast<std::uint8_t>(i);
      }
    }
  }
  choice.nodeSplit = choice.split[kBvhWidth - 1];
  p.asNode = area * kNodeTestCost + both[kBvhWidth - 1];
  const double asBlock = area * blockTestCost(p.count);
  const bool block = p.triangles && p.count <= blockLimit_ && asBlock <= p.asNode;
  choice.use = block ? LaneUse::kBlock : LaneUse::kNode;
  const double oneLane = block ? asBlock : p.asNode;
  p.cost[0] = oneLane;
  choice.split[0] = 0;
  for (std::size_t k = 1; k < kBvhWidth; ++k) {
    if (oneLane <= both[k]) choice.split[k] = 0;  // one lane where that is as cheap
    p.cost[k] = std::min(oneLane, both[k]);
  }
  return p;
}

int BvhLanePlan::lanesOf(std::uint32_t index,
                         std::array<std::uint32_t, kBvhWidth>& children) const {
  int n = 0;
  if (binary_[index].count > 0) {
    children[static_cast<std::size_t>(n++)] = index;
  } else {
    const int first = choices_[index].nodeSplit;
    spread(index + 1, first, children, n);
    spread(binary_[index].offset, kBvhWidth - first, children, n);
  }
  return n;
}

// Appends the binary nodes that take the `lanes` lanes chosen for binary
// node `index`'s subtree to children[n...].
void BvhLanePlan::spread(std::uint32_t index, int lanes,
                         std::array<std::uint32_t, kBvhWidth>& children, int& n) const {
  const int first = choices_[index].split[static_cast<std::size_t>(lanes - 1)];
  if (first == 0) {
    children[static_cast<std::size_t>(n++)] = index;
    return;
  }
  spread(index + 1, first, children, n);
  spread(binary_[index].offset, lanes - first, children, n);
}

}  // namespace glint
