#include <array>

#include "common/bvh.h"
#include "common/float_bits.h"

namespace glint {
namespace {

// A child waiting on the traversal stack: where it is, whether it is a leaf,
// and where the ray enters its box.
struct Pending {
  std::uint32_t offset;  // node index, or first entry in primIds for a leaf
  std::uint32_t count;   // primitives of a leaf; 0 for a node
  float entry;
};

// Depth-first walk of the 4-wide tree with a fixed stack. visitLeaf(offset,
// count) is called for each leaf whose box the ray enters before tMax; it
// returns true to stop the walk, and may lower tMax. With Nearest, the
// children of a node are visited nearest entry first, so that a close hit
// prunes the boxes behind it; a child whose entry now lies beyond tMax is
// dropped when popped, which is the same decision its box test would make.
template <bool Nearest, typename Visit>
void walk(const std::vector<BvhNode>& nodes, const Ray& ray, float& tMax, Visit visitLeaf) {
  if (nodes.empty()) return;  // all geometry may have been invalid
  const SlabRay4 slabRay(ray);
  // Each level leaves at most three siblings behind; a node adds four.
  std::array<Pending, 3 * kBvhMaxDepth + 4> stack;
  int top = 0;
  stack[top++] = {0, 0, 0.0f};
  while (top > 0) {
    const Pending current = stack[--top];
    if (current.entry > tMax) continue;
    if (current.count > 0) {
      if (visitLeaf(current.offset, current.count)) return;
      continue;
    }
    const BvhNode& node = nodes[current.offset];
    Float4 entry;
    // Unused lanes hold empty boxes, which no ray enters: no mask needed.
    const unsigned hits = intersectSlabs4(node.boxes, slabRay, 0.0f, tMax, &entry);
    // Push the children hit, farthest first, so that the nearest is popped next.
    const int first = top;
    for (int lane = 0; lane < 4; ++lane) {
      if (!(hits & (1u << lane))) continue;
      Pending p{node.offset[lane], node.count[lane], entry[lane]};
      int i = top++;
      if constexpr (Nearest) {
        for (; i > first && stack[i - 1].entry < p.entry; --i) stack[i] = stack[i - 1];
      }
      stack[i] = p;
    }
  }
}

}  // namespace

std::optional<Hit> Bvh::intersect(const Ray& ray, float tMax) const {
  std::optional<Hit> nearest;
  const WatertightRay w(ray);  // per ray, not per triangle
  walk<true>(nodes_, ray, tMax, [&](std::uint32_t offset, std::uint32_t count) {
    for (std::uint32_t i = offset; i < offset + count; ++i) {
      // One ulp beyond the nearest hit so far, so that a hit at exactly the
      // same distance reaches the tie-break of closerHit.
      const float limit = nearest ? nextFloatUp(tMax) : tMax;
      const std::optional<Hit> hit = geometry_->intersect(primIds_[i], ray, w, limit);
      if (hit && (!nearest || closerHit(*hit, *nearest))) {
        nearest = hit;
        tMax = hit->t;  // a later hit counts only if closer
      }
    }
    return false;
  });
  return nearest;
}

bool Bvh::occluded(const Ray& ray, float tMax) const {
  bool found = false;
  const WatertightRay w(ray);
  walk<false>(nodes_, ray, tMax, [&](std::uint32_t offset, std::uint32_t count) {
    for (std::uint32_t i = offset; i < offset + count; ++i) {
      if (geometry_->intersect(primIds_[i], ray, w, tMax)) {
        found = true;
        return true;
      }
    }
    return false;
  });
  return found;
}

}  // namespace glint
