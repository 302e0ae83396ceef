#include <array>
#include <bit>

#include "common/geometry/bvh.h"
#include "common/math/float_bits.h"

namespace glint {
namespace {

// A child waiting on the traversal stack: where it is, whether it is a leaf,
// and where the ray enters its box.
struct Pending {
  std::uint32_t offset;  // node index, or a leaf's first entry in primIds or its block
  std::uint32_t count;   // a leaf's BvhNode::count; 0 for a node
  float entry;
};

// Asks for the memory of a child the ray enters while the walk goes on: a
// node's four cache lines, or every other line of a 320-byte block (as fast
// as all five or six it straddles; a scalar leaf's primitives lie
// elsewhere). More rays per second on large scenes (docs/performance.md).
// Always inlined: GCC takes a function of nothing
// but prefetches for one without effect and drops its calls.
[[gnu::always_inline]] inline void prefetch(const std::vector<BvhNode>& nodes, const TriangleBlock* blocks,
                                            const Pending& child) {
  static_assert(sizeof(BvhNode) == 256 && sizeof(TriangleBlock) == 320, "the lines asked for below");
  if (child.count == 0) {
    const char* node = reinterpret_cast<const char*>(&nodes[child.offset]);
    __builtin_prefetch(node);
    __builtin_prefetch(node + 64);
    __builtin_prefetch(node + 128);
    __builtin_prefetch(node + 192);
  } else if (child.count & kBlockLeaf) {
    const char* block = reinterpret_cast<const char*>(blocks + child.offset);
    __builtin_prefetch(block);
    __builtin_prefetch(block + 128);
    __builtin_prefetch(block + 256);
  }
}

// Depth-first walk of the 8-wide tree with a fixed stack, V (Float4 or
// Float8) lanes per box test instruction; always inlined, so that the AVX2
// queries compile it for AVX2. visitLeaf(leaf) is called for each leaf
// whose box the ray enters before tMax; it returns true to stop the walk,
// and may lower tMax. With Nearest, the
// children of a node are visited nearest entry first, so that a close hit
// prunes the boxes behind it; a child whose entry now lies beyond tMax is
// dropped when popped, which is the same decision its box test would make.
template <typename V, bool Nearest, typename Visit>
[[gnu::always_inline]] inline void walk(const std::vector<BvhNode>& nodes, const TriangleBlock* blocks,
                                        const Ray& ray, float& tMax, const Visit& visitLeaf) {
  if (nodes.empty()) return;  // all geometry may have been invalid
  const SlabRay<V> slabRay(ray);
  // Each level leaves at most kBvhWidth - 1 siblings behind; a node adds kBvhWidth.
  std::array<Pending, (kBvhWidth - 1) * kBvhMaxDepth + kBvhWidth> stack;
  int top = 0;
  stack[top++] = {0, 0, 0.0f};
  while (top > 0) {
    const Pending current = stack[--top];
    if (current.entry > tMax) continue;
    if (current.count > 0) {
      if (visitLeaf(current)) return;
      continue;
    }
    const BvhNode& node = nodes[current.offset];
    alignas(32) float entry[kBvhWidth];
    // Unused lanes hold empty boxes, which no ray enters: no mask needed.
    const unsigned hits = intersectSlabs(node.boxes, slabRay, 0.0f, tMax, entry);
    // Push the children hit, farthest first, so that the nearest is popped
    // next. Unrolled, each lane's branch is predicted on its own: more rays
    // per second (docs/performance.md).
    const int first = top;
#pragma GCC unroll kBvhWidth
    for (int lane = 0; lane < kBvhWidth; ++lane) {
      if (!(hits & (1u << lane))) continue;
      Pending p{node.offset[lane], node.count[lane], entry[lane]};
      prefetch(nodes, blocks, p);
      int i = top++;
      if constexpr (Nearest) {
        for (; i > first && stack[i - 1].entry < p.entry; --i) stack[i] = stack[i - 1];
      }
      stack[i] = p;
    }
  }
}

// Calls visit(hit) for the hits among a block's lanes `used` (bit i: lane
// i), each found with the limit that limit() gives at that moment (as the
// scalar test would with it), until visit returns true; returns whether it
// did. limit() must not grow within the leaf beyond `bound`. The lanes
// below kTested are tested V at a time as far as the limit allows, then
// finished one by one: the same bits as the scalar test.
template <typename V, int kTested, typename Limit, typename Visit>
[[gnu::always_inline]] inline bool testLanes(const TriangleBlock& block, unsigned used, const Ray& ray,
                                             const WatertightRay& w, float bound, Limit limit, Visit visit) {
  constexpr int kLanes = kLanesOf<V>;
  for (int first = 0; first < kTested && (used >> first) != 0; first += kLanes) {
    const unsigned lanes = (used >> first) & ((1u << kLanes) - 1u);
    TriangleHits<V> hits;
    intersectTriangles(block.vertices, first, ray, w, lanes, bound, hits);
    for (unsigned left = hits.candidates; left != 0; left &= left - 1) {
      const int lane = std::countr_zero(left);
      if (const auto h = hits.lane(lane, w, limit())) {
        const std::uint32_t prim = block.prims[static_cast<std::size_t>(first + lane)];
        if (visit(Hit{h->t, prim, h->b0, h->b1, h->b2})) return true;
      }
    }
  }
  return false;
}

// testLanes for a block leaf: a block of up to four triangles in one test
// of four lanes (known at compile time to be one test: a loop that might
// run twice cost rays per second; docs/performance.md), a larger
// one V lanes at a time.
template <typename V, typename Limit, typename Visit>
[[gnu::always_inline]] inline bool testBlock(const TriangleBlock* blocks, const Pending& leaf, const Ray& ray,
                                             const WatertightRay& w, float bound, Limit limit, Visit visit) {
  const TriangleBlock& block = blocks[leaf.offset];
  const std::uint32_t count = leaf.count & ~kBlockLeaf;
  const unsigned used = (1u << count) - 1u;
  constexpr int kFour = kLanesOf<Float4>;
  if (count <= kFour) return testLanes<Float4, kFour>(block, used, ray, w, bound, limit, visit);
  return testLanes<V, kBlockTriangles>(block, used, ray, w, bound, limit, visit);
}

}  // namespace

template <typename V>
[[gnu::always_inline]] inline std::optional<Hit> Bvh::nearestHit(const Ray& ray, float tMax) const {
  std::optional<Hit> nearest;
  const WatertightRay w(ray);  // per ray, not per triangle
  // One ulp beyond the nearest hit so far, so that a hit at exactly the
  // same distance reaches the tie-break of closerHit.
  const auto limit = [&] { return nearest ? nextFloatUp(tMax) : tMax; };
  const auto keep = [&](const Hit& hit) {
    if (!nearest || closerHit(hit, *nearest)) {
      nearest = hit;
      tMax = hit.t;  // a later hit counts only if closer
    }
    return false;
  };
  walk<V, true>(arrays_.nodes, arrays_.blocks.get(), ray, tMax, [&](const Pending& leaf) {
    if (leaf.count & kBlockLeaf) {
      // A later limit is at most this one once a hit is known; before, the
      // first hit's distance may round a little beyond tMax: no bound.
      return testBlock<V>(arrays_.blocks.get(), leaf, ray, w, nearest ? limit() : kInfinity, limit, keep);
    }
    for (std::uint32_t i = leaf.offset; i < leaf.offset + leaf.count; ++i) {
      const std::optional<Hit> hit = geometry_->intersect(arrays_.primIds[i], ray, w, limit());
      if (hit) keep(*hit);
    }
    return false;
  });
  return nearest;
}

template <typename V>
[[gnu::always_inline]] inline bool Bvh::anyHit(const Ray& ray, float tMax) const {
  const WatertightRay w(ray);
  bool found = false;
  walk<V, false>(arrays_.nodes, arrays_.blocks.get(), ray, tMax, [&](const Pending& leaf) {
    if (leaf.count & kBlockLeaf) {
      const auto stop = [](const Hit&) { return true; };
      found = testBlock<V>(arrays_.blocks.get(), leaf, ray, w, tMax, [&] { return tMax; }, stop);
      return found;
    }
    for (std::uint32_t i = leaf.offset; i < leaf.offset + leaf.count; ++i) {
      if (geometry_->intersect(arrays_.primIds[i], ray, w, tMax)) {
        found = true;
        return true;
      }
    }
    return false;
  });
  return found;
}

std::optional<Hit> Bvh::intersect(const Ray& ray, float tMax, BoxTestWidth width) const {
#if defined(__x86_64__)
  if (width == BoxTestWidth::kEight && avx2Available()) return nearestHitEight(ray, tMax);
#endif
  return nearestHitFour(ray, tMax);
}

bool Bvh::occluded(const Ray& ray, float tMax, BoxTestWidth width) const {
#if defined(__x86_64__)
  if (width == BoxTestWidth::kEight && avx2Available()) return anyHitEight(ray, tMax);
#endif
  return anyHitFour(ray, tMax);
}

// Never inlined into intersect or occluded: there the four-lane walk's 6 KB
// stack frame and six saved registers came with every query, also those
// that went on to the eight-lane walk.
[[gnu::noinline]] std::optional<Hit> Bvh::nearestHitFour(const Ray& ray, float tMax) const {
  return nearestHit<Float4>(ray, tMax);
}

[[gnu::noinline]] bool Bvh::anyHitFour(const Ray& ray, float tMax) const { return anyHit<Float4>(ray, tMax); }

#if defined(__x86_64__)
GLINT_AVX2 std::optional<Hit> Bvh::nearestHitEight(const Ray& ray, float tMax) const {
  return nearestHit<Float8>(ray, tMax);
}

GLINT_AVX2 bool Bvh::anyHitEight(const Ray& ray, float tMax) const { return anyHit<Float8>(ray, tMax); }
#endif

}  // namespace glint
