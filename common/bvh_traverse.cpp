#include <array>
#include <cmath>

#include "common/bvh.h"
#include "common/float_bits.h"

namespace glint {
namespace {

// Depth-first walk of the flat tree with a fixed stack. visitLeafPrim is
// called for each primitive of each leaf whose box the ray enters before
// tMax; it returns true to stop the walk, and may lower tMax.
template <typename Visit>
void walk(const std::vector<BvhNode>& nodes, const Ray& ray, float& tMax, Visit visitLeaf) {
  if (nodes.empty()) return;  // all geometry may have been invalid
  const SlabRay slabRay(ray);
  std::array<std::uint32_t, kBvhMaxDepth> stack;
  int top = 0;
  std::uint32_t index = 0;
  while (true) {
    const BvhNode& node = nodes[index];
    if (intersectSlabs(node.bounds, slabRay, 0.0f, tMax)) {
      if (node.count > 0) {
        if (visitLeaf(node)) return;
      } else {
        // Visit the child on the near side of the split plane first, so that
        // a close hit prunes the far child's box.
        const bool farFirst = slabRay.nearIndex[node.axis] >= 3;
        stack[top++] = farFirst ? index + 1 : node.offset;
        index = farFirst ? node.offset : index + 1;
        continue;
      }
    }
    if (top == 0) return;
    index = stack[--top];
  }
}

}  // namespace

std::optional<Hit> Bvh::intersect(const Geometry& geometry, const Ray& ray, float tMax) const {
  std::optional<Hit> nearest;
  const WatertightRay w(ray);  // per ray, not per triangle
  walk(nodes_, ray, tMax, [&](const BvhNode& leaf) {
    for (std::uint32_t i = leaf.offset; i < leaf.offset + leaf.count; ++i) {
      // One ulp beyond the nearest hit so far, so that a hit at exactly the
      // same distance reaches the tie-break of closerHit.
      const float limit = nearest ? std::nextafter(tMax, kInfinity) : tMax;
      const std::optional<Hit> hit = geometry.intersect(primIds_[i], ray, w, limit);
      if (hit && (!nearest || closerHit(*hit, *nearest))) {
        nearest = hit;
        tMax = hit->t;  // a later hit counts only if closer
      }
    }
    return false;
  });
  return nearest;
}

bool Bvh::occluded(const Geometry& geometry, const Ray& ray, float tMax) const {
  bool found = false;
  const WatertightRay w(ray);
  walk(nodes_, ray, tMax, [&](const BvhNode& leaf) {
    for (std::uint32_t i = leaf.offset; i < leaf.offset + leaf.count; ++i) {
      if (geometry.intersect(primIds_[i], ray, w, tMax)) {
        found = true;
        return true;
      }
    }
    return false;
  });
  return found;
}

}  // namespace glint
