#pragma once

#include <cstring>

#include <glm/gtc/type_ptr.hpp>
#include <glm/vec3.hpp>

#include "common/ray.h"
#include "common/triangle.h"
#include "common/lanes.h"

namespace glint {

// Four triangles side by side, structure of arrays (a BVH leaf's block):
// v[k][axis][lane] is coordinate `axis` of vertex k of triangle `lane`.
struct Triangles4 {
  alignas(16) float v[3][3][4];

  void set(int lane, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
    const glm::vec3* p[3] = {&p0, &p1, &p2};
    for (int k = 0; k < 3; ++k) {
      for (int axis = 0; axis < 3; ++axis) v[k][axis][lane] = glm::value_ptr(*p[k])[axis];
    }
  }
};

// shearTriangle for four triangles at once: vertex k's sheared coordinates
// are x[k], y[k], z[k], lane by lane the same operations in the same order
// as the scalar step, so each lane holds the scalar step's exact values.
struct ShearedTriangles4 {
  Float4 x[3], y[3], z[3];

  ShearedTriangle lane(int i) const {
    return {{x[0][i], y[0][i], z[0][i]}, {x[1][i], y[1][i], z[1][i]}, {x[2][i], y[2][i], z[2][i]}};
  }
};

// Shears the lanes of `t` into `out` and returns those of `lanes` the ray may
// hit (bit i: lane i): their float edge functions are not of mixed signs and
// the hit lies in front of the origin and not beyond `bound` (as
// intersectSheared compares with its limit; infinity: no bound), or an edge
// function is zero (intersectSheared recomputes those in double). A lane left
// out is one intersectSheared rejects with any limit up to `bound`; the
// caller finishes the others with intersectSheared(out.lane(i), ...), which
// gives the scalar test's result.
inline unsigned shearTriangles4(const Triangles4& t, const Ray& ray, const WatertightRay& w, unsigned lanes,
                                float bound, ShearedTriangles4& out) {
  const float* origin = glm::value_ptr(ray.o);
  const int order[3] = {w.kx, w.ky, w.kz};
  for (int k = 0; k < 3; ++k) {
    Float4 d[3];
    for (int axis = 0; axis < 3; ++axis) {
      Float4 coordinate;
      std::memcpy(&coordinate, t.v[k][order[axis]], sizeof(Float4));
      d[axis] = coordinate - origin[order[axis]];
    }
    out.x[k] = d[0] + w.sx * d[2];
    out.y[k] = d[1] + w.sy * d[2];
    out.z[k] = d[2];
  }
  // The edge functions as intersectSheared computes them in float.
  const Float4 e0 = out.x[1] * out.y[2] - out.y[1] * out.x[2];
  const Float4 e1 = out.x[2] * out.y[0] - out.y[2] * out.x[0];
  const Float4 e2 = out.x[0] * out.y[1] - out.y[0] * out.x[1];
  const Float4 zero{};
  const Mask4 anyZero = (e0 == zero) | (e1 == zero) | (e2 == zero);
  const Mask4 mixed = ((e0 < zero) | (e1 < zero) | (e2 < zero)) & ((e0 > zero) | (e1 > zero) | (e2 > zero));
  // The determinant and the scaled distance as intersectSheared computes
  // them: a hit behind the origin (or none: det zero or not finite) is
  // rejected there whatever the limit.
  const Float4 det = e0 + e1 + e2;
  const Float4 tScaled = e0 * (out.z[0] * w.sz) + e1 * (out.z[1] * w.sz) + e2 * (out.z[2] * w.sz);
  const Mask4 finite = (det - det) == zero;  // false for inf and NaN
  const Float4 far = det * bound;
  const Mask4 inRange = ((det < zero) & (tScaled < zero) & (tScaled >= far)) |
                        ((det > zero) & (tScaled > zero) & (tScaled <= far));
  return laneBits(anyZero | (~mixed & finite & inRange)) & lanes;
}

}  // namespace glint
