#pragma once

// The collapse's cost pass (after Ylitie, Karras and Laine 2017, "Efficient
// Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs", section
// 4.1): which binary nodes take the lanes of each 8-wide node, chosen bottom
// up for the least SAH cost. bvh_collapse.cpp makes the wide nodes from it.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>

#include "common/geometry/bvh_collapse.h"

namespace glint {

// What the cost pass weighs, relative to one 8-wide node's box test: one
// primitive tested alone, and a block leaf of n triangles. A block costs
// more the more of its lanes are in use, as each candidate lane is finished
// on its own: priced alike whatever its count, the pass would merge
// neighbouring blocks wherever their union's area is less than the sum of
// theirs, and the bunny's rays would test a fifth more blocks and triangles
// (counted visits, docs/performance.md).
constexpr double kNodeTestCost = 1.0;
constexpr double kTriangleTestCost = 1.0;
constexpr double blockTestCost(std::uint32_t n) {
  return 1.0 + 0.125 * n;
}

// What becomes of a binary node that takes one lane of an 8-wide node.
enum class LaneUse : std::uint8_t { kNode, kLeaf, kBlock };

class BvhLanePlan {
 public:
  // Whether a binary leaf holds triangles only (a block holds no sphere).
  using TrianglesOnly = std::function<bool(const BinaryNode& leaf)>;
  // The plan for the tree rooted at binary[0], whose nodes lie in
  // binary[0, capacity): a node in one lane may be a leaf of its
  // primitives, a block leaf of two to blockLimit triangles, or a node of its
  // own; a binary leaf may only be a leaf (a block where it can).
  BvhLanePlan(const BinaryNode* binary, std::size_t capacity, std::size_t blockLimit,
              const TrianglesOnly& trianglesOnly);

  // The tree's SAH cost: its root as an 8-wide node.
  double cost() const { return cost_; }
  // What binary node `index` becomes where it takes a lane.
  LaneUse use(std::uint32_t index) const { return choices_[index].use; }
  // The binary nodes that take the lanes of the 8-wide node made for binary
  // node `index` (the node itself where it is a leaf: a tree of one leaf),
  // in children[0, n); returns n.
  int lanesOf(std::uint32_t index, std::array<std::uint32_t, kBvhWidth>& children) const;

  // The choice for one binary node, kept until the collapse is made.
  struct Choice {
    // split[k - 1]: of k lanes, how many the node's subtree gives its first
    // child's (the rest go to the second's); 0: the subtree takes one lane.
    std::array<std::uint8_t, kBvhWidth> split;
    std::uint8_t nodeSplit;  // as a node of its own: its kBvhWidth lanes, split so
    LaneUse use;             // in one lane
  };

 private:
  // The costs of a binary node's subtree in up to k lanes (cost[k - 1]), and
  // what pricing a block of it needs.
  struct Placement {
    std::array<double, kBvhWidth> cost;
    double asNode;        // in one lane as a node of its own (interior nodes)
    std::uint32_t count;  // primitives
    bool triangles;       // no sphere among them
  };
  Placement choose(std::uint32_t index, const TrianglesOnly& trianglesOnly);
  void spread(std::uint32_t index, int lanes, std::array<std::uint32_t, kBvhWidth>& children,
              int& n) const;

  const BinaryNode* binary_;
  std::size_t blockLimit_;
  std::unique_ptr<Choice[]> choices_;  // by binary node index (only the tree's are written)
  double cost_ = 0.0;
};

}  // namespace glint
