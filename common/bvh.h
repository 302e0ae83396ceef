#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "common/bounds.h"
#include "common/geometry.h"
#include "common/ray.h"

namespace glint {

enum class BvhBuilder {
  kQSplit,  // the thesis's: midpoint of the node's box, axis cycling x, y, z per level
  kSah,     // binned surface area heuristic (Wald 2007)
};

// Every tuning knob of the BVH build, with its default.
struct BvhSettings {
  BvhBuilder builder = BvhBuilder::kSah;
  int maxLeafSize = 4;     // a node with at most this many primitives may become a leaf
  int sahBins = 16;        // centroid bins per axis for the SAH
  float traversalCost = 1.0f;  // SAH cost of visiting a node, relative to one primitive test
};

// One node of the flattened tree, 32 bytes, depth-first order:
//   bytes  0-23  bounds (min xyz, max xyz as float)
//   bytes 24-27  offset: leaf -> first entry in Bvh::primIds;
//                interior -> index of the second child (the first child is
//                the next node)
//   bytes 28-29  count: primitives in a leaf, 0 for an interior node
//   byte  30     axis the interior node was split on (near child first)
//   byte  31     padding
struct BvhNode {
  Bounds3 bounds;
  std::uint32_t offset;
  std::uint16_t count;
  std::uint8_t axis;
  std::uint8_t pad;
};
static_assert(sizeof(BvhNode) == 32, "BvhNode is documented as 32 bytes");

// Traversal keeps a fixed stack; the builder guarantees the tree is no deeper.
constexpr int kBvhMaxDepth = 64;

// What the builder sees of a primitive.
struct BuildPrimitive {
  Bounds3 bounds;
  std::uint32_t id;
};

class Bvh {
 public:
  static Bvh build(std::vector<BuildPrimitive> prims, const BvhSettings& settings);
  static Bvh build(const Geometry& geometry, const BvhSettings& settings);

  // Nearest hit with t < tMax; boxes are skipped once they lie beyond the
  // nearest hit so far.
  std::optional<Hit> intersect(const Geometry& geometry, const Ray& ray, float tMax) const;
  // Any hit with t < tMax (shadow rays): stops at the first one.
  bool occluded(const Geometry& geometry, const Ray& ray, float tMax) const;

  const std::vector<BvhNode>& nodes() const { return nodes_; }
  const std::vector<std::uint32_t>& primIds() const { return primIds_; }
  int depth() const { return depth_; }

 private:
  friend class BvhBuilderImpl;
  std::vector<BvhNode> nodes_;
  std::vector<std::uint32_t> primIds_;
  int depth_ = 0;
};

}  // namespace glint
