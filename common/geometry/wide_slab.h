#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "common/geometry/bounds.h"
#include "common/math/float_bits.h"
#include "common/math/lanes.h"
#include "common/geometry/ray.h"

namespace glint {

// Children per BVH node: the boxes that one slab test tests together.
constexpr int kBvhWidth = 8;

// kBvhWidth boxes as a structure of arrays: planes[0..2] are min x, y, z and
// planes[3..5] max x, y, z; lane i of each is box i. An unused lane holds the
// empty box (min +inf, max -inf), which no ray enters.
struct WideBoxes {
  alignas(32) float planes[6][kBvhWidth];

  void set(int lane, const Bounds3& b) {
    for (int axis = 0; axis < 3; ++axis) {
      planes[axis][lane] = b.min[axis];
      planes[axis + 3][lane] = b.max[axis];
    }
  }
  Bounds3 get(int lane) const {
    Bounds3 b;
    for (int axis = 0; axis < 3; ++axis) {
      b.min[axis] = planes[axis][lane];
      b.max[axis] = planes[axis + 3][lane];
    }
    return b;
  }
};

// The per-ray part of the slab test, computed once per traversal: origin
// and 1/d broadcast to the lanes of V (Float4 or Float8), and which of min /
// max is the near plane on each axis (by the sign bit of 1/d, as the scalar
// test picks it).
template <typename V>
struct SlabRay {
  V o[3];
  V invD[3];
  int nearPlane[3];
  int farPlane[3];

  [[gnu::always_inline]] explicit SlabRay(const Ray& ray) {
    // Through plain pointers: glm's v[i] with a run-time i is a switch.
    const float* origin = glm::value_ptr(ray.o);
    const float* inverse = glm::value_ptr(ray.invD);
    for (int axis = 0; axis < 3; ++axis) {
      o[axis] = V{} + origin[axis];
      invD[axis] = V{} + inverse[axis];
      const bool negative = std::signbit(inverse[axis]);
      nearPlane[axis] = negative ? axis + 3 : axis;
      farPlane[axis] = negative ? axis : axis + 3;
    }
  }
};

// Robust slab test (Williams et al. 2005, "An Efficient and Robust Ray-Box
// Intersection Algorithm"; Ize 2013, "Robust BVH Ray Traversal") on the
// kBvhWidth boxes, as many at once as V has lanes: every lane the same
// operations, so Float4 and Float8 give the same bits. The far distance is
// scaled by 1 + 2 gamma(3) so rounding never culls a box the ray touches,
// and the comparisons are ordered so that a NaN (0 * inf, an origin exactly
// on a slab plane of an axis the ray is parallel to) never replaces the
// running interval: boundaries count as inside. Returns a bit per lane
// (bit i: the ray enters box i between tMin and tMax) and each lane's entry
// distance in entry[i] (for the lanes hit: at least tMin, never NaN).
template <typename V>
[[gnu::always_inline]] inline unsigned intersectSlabs(const WideBoxes& boxes, const SlabRay<V>& r, float tMin,
                                                      float tMax, float* entry) {
  constexpr int kLanes = kLanesOf<V>;
  static_assert(kBvhWidth % kLanes == 0, "a node's boxes are whole vectors");
  constexpr float kFarScale = 1.0f + 2.0f * gamma(3);
  unsigned hits = 0;
  for (int first = 0; first < kBvhWidth; first += kLanes) {
    V t0 = V{} + tMin;
    V t1 = V{} + tMax;
    for (int axis = 0; axis < 3; ++axis) {
      V nearPlane;
      V farPlane;
      std::memcpy(&nearPlane, boxes.planes[r.nearPlane[axis]] + first, sizeof(V));
      std::memcpy(&farPlane, boxes.planes[r.farPlane[axis]] + first, sizeof(V));
      const V tNear = (nearPlane - r.o[axis]) * r.invD[axis];
      const V tFar = (farPlane - r.o[axis]) * r.invD[axis] * kFarScale;
      t0 = tNear > t0 ? tNear : t0;  // a NaN leaves the interval unchanged
      t1 = tFar < t1 ? tFar : t1;
    }
    std::memcpy(entry + first, &t0, sizeof(V));
    hits |= laneBits(t0 <= t1) << first;
  }
  return hits;
}

}  // namespace glint
