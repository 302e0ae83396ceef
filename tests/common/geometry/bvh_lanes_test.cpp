#include "common/geometry/bvh_lanes.h"

#include <algorithm>
#include <limits>
#include <map>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace glint {
namespace {

// A random binary tree in the builder's layout (depth first, an interior
// node's first child next to it, its second at `offset`), its leaves'
// primitives in order, some leaves of spheres.
struct RandomTree {
  std::vector<BinaryNode> nodes;
  std::map<std::uint32_t, bool> sphereLeaf;  // by a leaf's first primitive
  std::mt19937 rng;
  std::uint32_t prims = 0;

  explicit RandomTree(unsigned seed) : rng(seed) {}

  std::uint32_t make(int leaves) {
    const auto index = static_cast<std::uint32_t>(nodes.size());
    nodes.emplace_back();
    if (leaves == 1) {
      std::uniform_real_distribution<float> corner(0.0f, 10.0f), extent(0.1f, 4.0f);
      const glm::vec3 min(corner(rng), corner(rng), corner(rng));
      const auto count = std::uniform_int_distribution<std::uint32_t>(1, 6)(rng);
      nodes[index] = {min, min + glm::vec3(extent(rng), extent(rng), extent(rng)), prims, count};
      sphereLeaf[prims] = std::uniform_int_distribution<int>(0, 4)(rng) == 0;
      prims += count;
      return index;
    }
    const int first = std::uniform_int_distribution<int>(1, leaves - 1)(rng);
    make(first);
    const std::uint32_t second = make(leaves - first);
    const BinaryNode& a = nodes[index + 1];
    const BinaryNode& b = nodes[second];
    nodes[index] = {glm::min(a.min, b.min), glm::max(a.max, b.max), second, 0};
    return index;
  }
};

// The least SAH cost of every placement, found by listing them all: each
// set of at most kBvhWidth binary nodes whose subtrees together make up a
// node's subtree (a cut), and for each node in a lane each thing it may
// become. Independent of the plan's running minimum over lane counts.
class BruteForce {
 public:
  BruteForce(const std::vector<BinaryNode>& nodes, const std::map<std::uint32_t, bool>& sphereLeaf,
             std::uint32_t blockLimit)
      : nodes_(nodes), sphereLeaf_(sphereLeaf), blockLimit_(blockLimit) {}

  double rootCost() {
    const BinaryNode& root = nodes_[0];
    if (root.count > 0) return area(0) * kNodeTestCost + inLane(0);
    return asNode(0);
  }

 private:
  using Cut = std::vector<std::uint32_t>;

  double area(std::uint32_t i) const { return nodes_[i].bounds().surfaceArea(); }
  bool isLeaf(std::uint32_t i) const { return nodes_[i].count > 0; }
  std::uint32_t second(std::uint32_t i) const { return nodes_[i].offset; }

  void stats(std::uint32_t i, std::uint32_t& count, bool& triangles) const {
    if (isLeaf(i)) {
      count += nodes_[i].count;
      triangles = triangles && !sphereLeaf_.at(nodes_[i].offset);
      return;
    }
    stats(i + 1, count, triangles);
    stats(second(i), count, triangles);
  }

  const std::vector<Cut>& cutsOf(std::uint32_t i) {
    if (const auto found = cuts_.find(i); found != cuts_.end()) return found->second;
    std::vector<Cut> result{{i}};
    if (!isLeaf(i)) {
      for (const Cut& x : cutsOf(i + 1)) {
        for (const Cut& y : cutsOf(second(i))) {
          if (x.size() + y.size() > kBvhWidth) continue;
          Cut both = x;
          both.insert(both.end(), y.begin(), y.end());
          result.push_back(both);
        }
      }
    }
    return cuts_[i] = result;
  }

  double asNode(std::uint32_t i) {
    double best = std::numeric_limits<double>::infinity();
    for (const Cut& x : cutsOf(i + 1)) {
      for (const Cut& y : cutsOf(second(i))) {
        if (x.size() + y.size() > kBvhWidth) continue;
        double sum = 0.0;
        for (const std::uint32_t c : x) sum += inLane(c);
        for (const std::uint32_t c : y) sum += inLane(c);
        best = std::min(best, sum);
      }
    }
    return area(i) * kNodeTestCost + best;
  }

  double inLane(std::uint32_t i) {
    if (const auto found = lane_.find(i); found != lane_.end()) return found->second;
    std::uint32_t count = 0;
    bool triangles = true;
    stats(i, count, triangles);
    const bool block = triangles && count <= blockLimit_ && (count > 1 || !isLeaf(i));
    double best = std::numeric_limits<double>::infinity();
    if (block) best = area(i) * blockTestCost(count);
    if (isLeaf(i) && !block) best = area(i) * kTriangleTestCost * count;
    if (!isLeaf(i)) best = std::min(best, asNode(i));
    return lane_[i] = best;
  }

  const std::vector<BinaryNode>& nodes_;
  const std::map<std::uint32_t, bool>& sphereLeaf_;
  std::uint32_t blockLimit_;
  std::map<std::uint32_t, std::vector<Cut>> cuts_;
  std::map<std::uint32_t, double> lane_;
};

// The cost of the wide tree the plan describes, summed over the nodes and
// leaves it makes; checks on the way that every node has one to kBvhWidth
// lanes and that each primitive lies in exactly one leaf.
double planCost(const BvhLanePlan& plan, const RandomTree& tree, std::uint32_t i, std::vector<int>& seen) {
  std::array<std::uint32_t, kBvhWidth> lanes{};
  const int n = plan.lanesOf(i, lanes);
  EXPECT_GE(n, 1);
  EXPECT_LE(n, kBvhWidth);
  double cost = tree.nodes[i].bounds().surfaceArea() * kNodeTestCost;
  for (int lane = 0; lane < n; ++lane) {
    const std::uint32_t c = lanes[static_cast<std::size_t>(lane)];
    const BinaryNode& node = tree.nodes[c];
    const double area = node.bounds().surfaceArea();
    if (plan.use(c) == LaneUse::kNode) {
      EXPECT_EQ(node.count, 0u) << "a binary leaf is never a node";
      cost += planCost(plan, tree, c, seen);
      continue;
    }
    // A leaf's or block's primitives: the subtree's range.
    std::uint32_t first = c, last = c;
    while (tree.nodes[first].count == 0) ++first;
    while (tree.nodes[last].count == 0) last = tree.nodes[last].offset;
    const std::uint32_t begin = tree.nodes[first].offset;
    const std::uint32_t count = tree.nodes[last].offset + tree.nodes[last].count - begin;
    for (std::uint32_t p = begin; p < begin + count; ++p) ++seen[p];
    if (plan.use(c) == LaneUse::kLeaf) {
      EXPECT_GT(node.count, 0u) << "only a binary leaf is a plain leaf";
      cost += area * kTriangleTestCost * count;
    } else {
      EXPECT_GE(count, 2u);
      cost += area * blockTestCost(count);
    }
  }
  return cost;
}

// On random trees of 1 to 14 leaves, with blocks of up to eight and up to
// four triangles: the plan's cost is the least of all placements, and the
// wide tree it describes costs what it says, with every primitive once.
TEST(BvhLanePlan, CostIsTheLeastOfAllPlacements) {
  int blocks = 0, nodes = 0;
  for (unsigned seed = 0; seed < 300; ++seed) {
    RandomTree tree(seed);
    tree.make(1 + static_cast<int>(seed % 14));
    for (const std::uint32_t limit : {8u, 4u}) {
      const auto trianglesOnly = [&](const BinaryNode& leaf) { return !tree.sphereLeaf.at(leaf.offset); };
      const BvhLanePlan plan(tree.nodes.data(), tree.nodes.size(), limit, trianglesOnly);
      const double best = BruteForce(tree.nodes, tree.sphereLeaf, limit).rootCost();
      EXPECT_NEAR(plan.cost(), best, 1e-9 * best) << "seed " << seed << " limit " << limit;
      std::vector<int> seen(tree.prims, 0);
      EXPECT_NEAR(planCost(plan, tree, 0, seen), plan.cost(), 1e-9 * best) << "seed " << seed;
      EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(tree.prims)) << "seed " << seed;
      for (std::uint32_t i = 0; i < tree.nodes.size(); ++i) {
        blocks += plan.use(i) == LaneUse::kBlock && tree.nodes[i].count == 0 ? 1 : 0;
        nodes += plan.use(i) == LaneUse::kNode && i != 0 ? 1 : 0;
      }
    }
  }
  // The trees call for every choice: blocks of several leaves, nodes below the root.
  EXPECT_GT(blocks, 50);
  EXPECT_GT(nodes, 50);
}

}  // namespace
}  // namespace glint
