#pragma once

// A block leaf's triangles and their watertight test, several lanes per
// instruction (Float4, or Float8 in functions compiled for AVX2), each lane
// the scalar test's operations (common/geometry/triangle.h) in its order.

#include <cstring>
#include <optional>

#include <glm/gtc/type_ptr.hpp>
#include <glm/vec3.hpp>

#include "common/math/float_bits.h"
#include "common/geometry/ray.h"
#include "common/geometry/triangle.h"
#include "common/math/lanes.h"

namespace glint {

// The most triangles a block leaf holds: one eight-lane test. Blocks of
// eight instead of four: a large mesh's tree has half the nodes, and its
// rays are faster (docs/performance.md).
constexpr int kBlockTriangles = 8;

// A block leaf's triangles side by side, structure of arrays:
// v[k][axis][lane] is coordinate `axis` of vertex k of triangle `lane`.
struct TriangleLanes {
  alignas(32) float v[3][3][kBlockTriangles];

  void set(int lane, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
    const glm::vec3* p[3] = {&p0, &p1, &p2};
    for (int k = 0; k < 3; ++k) {
      for (int axis = 0; axis < 3; ++axis) v[k][axis][lane] = glm::value_ptr(*p[k])[axis];
    }
  }
};

// shearTriangle for kLanesOf<V> triangles at once: vertex k's sheared
// coordinates are x[k], y[k], z[k], lane by lane the same operations in the
// same order as the scalar step, so each lane holds the scalar step's exact
// values.
template <typename V>
struct ShearedTriangles {
  V x[3], y[3], z[3];

  ShearedTriangle lane(int i) const {
    return {{x[0][i], y[0][i], z[0][i]}, {x[1][i], y[1][i], z[1][i]}, {x[2][i], y[2][i], z[2][i]}};
  }
};

// The watertight test (intersectTriangle) for kLanesOf<V> triangles at
// once, lane by lane the same operations in the same order, so that each
// lane holds the scalar test's exact values: intersectTriangles computes
// what does not depend on the limit, lane(i, tMax) finishes lane i with a
// limit.
template <typename V>
struct TriangleHits {
  ShearedTriangles<V> sheared;
  V zScaled[3];     // the sheared z, scaled by WatertightRay::sz
  V e0, e1, e2;     // the edge functions in float
  V det, tScaled;   // the sum of the edge functions, the distance scaled by it
  V t, b0, b1, b2;  // the hit (lanes in `finished`)
  unsigned candidates;  // lanes the ray may hit with a limit up to the bound
  unsigned rounded;     // candidates with an edge function exactly zero
  unsigned finished;    // the other candidates whose t lies beyond its error bound

  // intersectSheared(sheared.lane(i), w, tMax) for a tMax up to the bound:
  // lanes that are no candidates miss, rounded lanes are finished by it
  // (their edge functions recomputed in double), the others here.
  std::optional<TriangleHit> lane(int i, const WatertightRay& w, float tMax) const {
    const unsigned bit = 1u << i;
    if (!(candidates & bit)) return std::nullopt;
    if (rounded & bit) return intersectSheared(sheared.lane(i), w, tMax);
    if (!(finished & bit)) return std::nullopt;
    // The limit as intersectSheared applies it (the signs are checked).
    const float far = tMax * det[i];
    if (det[i] < 0.0f ? tScaled[i] < far : tScaled[i] > far) return std::nullopt;
    return TriangleHit{t[i], b0[i], b1[i], b2[i]};
  }
};

// Shears lanes [first, first + kLanesOf<V>) of `t` (step one of
// intersectTriangle) and computes the edge functions in float: fills
// sheared, e0-e2, det and tScaled, and returns the lanes of `lanes` (bit i:
// lane first + i) the ray may hit: their edge functions are not of mixed
// signs and the hit lies in front of the origin and not beyond `bound` (as
// intersectSheared compares with its limit; infinity: no bound), or an edge
// function is zero (those lanes' bits also go to `rounded`).
template <typename V>
[[gnu::always_inline]] inline unsigned shearTriangles(const TriangleLanes& t, int first, const Ray& ray,
                                                      const WatertightRay& w, unsigned lanes, float bound,
                                                      TriangleHits<V>& out) {
  using Mask = decltype(V{} < V{});
  const float* origin = glm::value_ptr(ray.o);
  const int order[3] = {w.kx, w.ky, w.kz};
  ShearedTriangles<V>& s = out.sheared;
  for (int k = 0; k < 3; ++k) {
    V d[3];
    for (int axis = 0; axis < 3; ++axis) {
      V coordinate;
      std::memcpy(&coordinate, t.v[k][order[axis]] + first, sizeof(V));
      d[axis] = coordinate - origin[order[axis]];
    }
    s.x[k] = d[0] + w.sx * d[2];
    s.y[k] = d[1] + w.sy * d[2];
    s.z[k] = d[2];
    out.zScaled[k] = d[2] * w.sz;
  }
  out.e0 = s.x[1] * s.y[2] - s.y[1] * s.x[2];
  out.e1 = s.x[2] * s.y[0] - s.y[2] * s.x[0];
  out.e2 = s.x[0] * s.y[1] - s.y[0] * s.x[1];
  const V zero{};
  const Mask anyZero = (out.e0 == zero) | (out.e1 == zero) | (out.e2 == zero);
  const Mask mixed = ((out.e0 < zero) | (out.e1 < zero) | (out.e2 < zero)) &
                     ((out.e0 > zero) | (out.e1 > zero) | (out.e2 > zero));
  // A hit behind the origin (or none: det zero or not finite) is rejected
  // by intersectSheared whatever the limit.
  out.det = out.e0 + out.e1 + out.e2;
  out.tScaled = out.e0 * out.zScaled[0] + out.e1 * out.zScaled[1] + out.e2 * out.zScaled[2];
  const Mask finite = (out.det - out.det) == zero;  // false for inf and NaN
  const V far = out.det * bound;
  const Mask inRange = ((out.det < zero) & (out.tScaled < zero) & (out.tScaled >= far)) |
                       ((out.det > zero) & (out.tScaled > zero) & (out.tScaled <= far));
  out.rounded = laneBits(anyZero) & lanes;
  return laneBits(anyZero | (~mixed & finite & inRange)) & lanes;
}

// Step two for the candidates without a zero edge function: the distance,
// its error bound (pbrt-v4 6.8.4) and the barycentrics, as intersectSheared.
template <typename V>
[[gnu::always_inline]] inline void finishTriangles(TriangleHits<V>& h) {
  const ShearedTriangles<V>& s = h.sheared;
  const V invDet = 1.0f / h.det;
  h.t = h.tScaled * invDet;
  V maxZt, maxXt, maxYt, maxE, absInvDet;
  maxAbsOf3(h.zScaled[0], h.zScaled[1], h.zScaled[2], maxZt);
  maxAbsOf3(s.x[0], s.x[1], s.x[2], maxXt);
  maxAbsOf3(s.y[0], s.y[1], s.y[2], maxYt);
  const V deltaZ = gamma(3) * maxZt;
  const V deltaX = gamma(5) * (maxXt + maxZt);
  const V deltaY = gamma(5) * (maxYt + maxZt);
  const V deltaE = 2.0f * (gamma(2) * maxXt * maxYt + deltaY * maxXt + deltaX * maxYt);
  maxAbsOf3(h.e0, h.e1, h.e2, maxE);
  absLanes(invDet, absInvDet);
  const V deltaT = 3.0f * (gamma(3) * maxE * maxZt + deltaE * maxZt + deltaZ * maxE) * absInvDet;
  h.finished = ~laneBits(h.t <= deltaT) & h.candidates & ~h.rounded;
  h.b0 = h.e0 * invDet;
  h.b1 = h.e1 * invDet;
  h.b2 = h.e2 * invDet;
}

// The test of lanes [first, first + kLanesOf<V>) of `t`, those of them in
// `lanes` (bit i: lane first + i), for limits up to `bound` (infinity:
// none), into h; finish each lane with h.lane(i, w, tMax).
template <typename V>
[[gnu::always_inline]] inline void intersectTriangles(const TriangleLanes& t, int first, const Ray& ray,
                                                      const WatertightRay& w, unsigned lanes, float bound,
                                                      TriangleHits<V>& h) {
  h.candidates = shearTriangles(t, first, ray, w, lanes, bound, h);
  h.finished = 0;
  if (h.candidates & ~h.rounded) finishTriangles(h);
}

}  // namespace glint
