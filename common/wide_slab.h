#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "common/bounds.h"
#include "common/float_bits.h"
#include "common/lanes.h"
#include "common/ray.h"

namespace glint {

// Four boxes as a structure of arrays: planes[0..2] are min x, y, z and
// planes[3..5] max x, y, z; lane i of each is box i. An unused lane holds the
// empty box (min +inf, max -inf), which no ray enters.
struct Boxes4 {
  alignas(16) float planes[6][4];

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

// The per-ray part of the 4-box test, computed once per traversal: origin
// and 1/d broadcast to four lanes, and which of min / max is the near plane
// on each axis (by the sign bit of 1/d, as the scalar test picks it).
struct SlabRay4 {
  Float4 o[3];
  Float4 invD[3];
  int nearPlane[3];
  int farPlane[3];

  explicit SlabRay4(const Ray& ray) {
    // Through plain pointers: glm's v[i] with a run-time i is a switch.
    const float* origin = glm::value_ptr(ray.o);
    const float* inverse = glm::value_ptr(ray.invD);
    for (int axis = 0; axis < 3; ++axis) {
      o[axis] = Float4{} + origin[axis];
      invD[axis] = Float4{} + inverse[axis];
      const bool negative = std::signbit(inverse[axis]);
      nearPlane[axis] = negative ? axis + 3 : axis;
      farPlane[axis] = negative ? axis : axis + 3;
    }
  }
};

// Robust slab test (Williams et al. 2005, "An Efficient and Robust Ray-Box
// Intersection Algorithm"; Ize 2013, "Robust BVH Ray Traversal") on four
// boxes at once. The far distance is scaled by 1 + 2 gamma(3) so rounding
// never culls a box the ray touches, and the comparisons are ordered so that
// a NaN (0 * inf, an origin exactly on a slab plane of an axis the ray is
// parallel to) never replaces the running interval: boundaries count as
// inside. Returns a bit per lane (bit i: the ray enters box i between tMin
// and tMax) and each lane's entry distance in *entry (for the lanes hit: at
// least tMin, never NaN).
inline unsigned intersectSlabs4(const Boxes4& boxes, const SlabRay4& r, float tMin, float tMax,
                                Float4* entry) {
  constexpr float kFarScale = 1.0f + 2.0f * gamma(3);
  Float4 t0 = Float4{} + tMin;
  Float4 t1 = Float4{} + tMax;
  for (int axis = 0; axis < 3; ++axis) {
    Float4 nearPlane;
    Float4 farPlane;
    std::memcpy(&nearPlane, boxes.planes[r.nearPlane[axis]], sizeof(Float4));
    std::memcpy(&farPlane, boxes.planes[r.farPlane[axis]], sizeof(Float4));
    const Float4 tNear = (nearPlane - r.o[axis]) * r.invD[axis];
    const Float4 tFar = (farPlane - r.o[axis]) * r.invD[axis] * kFarScale;
    t0 = tNear > t0 ? tNear : t0;  // a NaN leaves the interval unchanged
    t1 = tFar < t1 ? tFar : t1;
  }
  *entry = t0;
  return laneBits(t0 <= t1);
}

}  // namespace glint
