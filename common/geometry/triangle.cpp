#include "common/geometry/triangle.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "common/math/float_bits.h"

namespace glint {
namespace {

// Through a plain pointer: glm's v[i] with a run-time i is a switch.
glm::vec3 permute(const glm::vec3& v, int x, int y, int z) {
  const float* p = glm::value_ptr(v);
  return {p[x], p[y], p[z]};
}

// a*b - c*d in plain float arithmetic: fl(a*b) - fl(c*d) is exactly the
// negation of fl(c*d) - fl(a*b), which the shared-edge guarantee needs.
float edge(float ax, float by, float ay, float bx) { return ax * by - ay * bx; }

float edgeDouble(float ax, float by, float ay, float bx) {
  return static_cast<float>(double(ax) * double(by) - double(ay) * double(bx));
}

// intersectSheared's body, inlined into both tests (a call here costs
// the scalar test several percent).
[[gnu::always_inline]] inline std::optional<TriangleHit> finishSheared(ShearedTriangle s, const WatertightRay& w,
                                                                       float tMax) {
  glm::vec3& a = s.a;
  glm::vec3& b = s.b;
  glm::vec3& c = s.c;
  const float sz = w.sz;
  float e0 = edge(b.x, c.y, b.y, c.x);
  float e1 = edge(c.x, a.y, c.y, a.x);
  float e2 = edge(a.x, b.y, a.y, b.x);
  if (e0 == 0.0f || e1 == 0.0f || e2 == 0.0f) {
    e0 = edgeDouble(b.x, c.y, b.y, c.x);
    e1 = edgeDouble(c.x, a.y, c.y, a.x);
    e2 = edgeDouble(a.x, b.y, a.y, b.x);
  }
  if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) {
    return std::nullopt;
  }
  const float det = e0 + e1 + e2;
  if (det == 0.0f || !std::isfinite(det)) return std::nullopt;

  a.z *= sz;
  b.z *= sz;
  c.z *= sz;
  const float tScaled = e0 * a.z + e1 * b.z + e2 * c.z;
  if (det < 0.0f && (tScaled >= 0.0f || tScaled < tMax * det)) return std::nullopt;
  if (det > 0.0f && (tScaled <= 0.0f || tScaled > tMax * det)) return std::nullopt;

  const float invDet = 1.0f / det;
  const float t = tScaled * invDet;

  // Conservative bound on the error of t (pbrt-v4 6.8.4): reject hits that
  // are not certainly in front of the origin.
  const float maxZt = std::max({std::abs(a.z), std::abs(b.z), std::abs(c.z)});
  const float maxXt = std::max({std::abs(a.x), std::abs(b.x), std::abs(c.x)});
  const float maxYt = std::max({std::abs(a.y), std::abs(b.y), std::abs(c.y)});
  const float deltaZ = gamma(3) * maxZt;
  const float deltaX = gamma(5) * (maxXt + maxZt);
  const float deltaY = gamma(5) * (maxYt + maxZt);
  const float deltaE = 2.0f * (gamma(2) * maxXt * maxYt + deltaY * maxXt + deltaX * maxYt);
  const float maxE = std::max({std::abs(e0), std::abs(e1), std::abs(e2)});
  const float deltaT =
      3.0f * (gamma(3) * maxE * maxZt + deltaE * maxZt + deltaZ * maxE) * std::abs(invDet);
  if (t <= deltaT) return std::nullopt;

  return TriangleHit{t, e0 * invDet, e1 * invDet, e2 * invDet};
}

}  // namespace

std::optional<TriangleHit> intersectTriangle(const Ray& ray, const glm::vec3& p0,
                                             const glm::vec3& p1, const glm::vec3& p2, float tMax) {
  return intersectTriangle(ray, WatertightRay(ray), p0, p1, p2, tMax);
}

std::optional<TriangleHit> intersectTriangle(const Ray& ray, const WatertightRay& w, const glm::vec3& p0,
                                             const glm::vec3& p1, const glm::vec3& p2, float tMax) {
  return finishSheared(shearTriangle(ray, w, p0, p1, p2), w, tMax);
}

ShearedTriangle shearTriangle(const Ray& ray, const WatertightRay& w, const glm::vec3& p0, const glm::vec3& p1,
                              const glm::vec3& p2) {
  const auto shear = [&w](glm::vec3 v) { return glm::vec3(v.x + w.sx * v.z, v.y + w.sy * v.z, v.z); };
  return {shear(permute(p0 - ray.o, w.kx, w.ky, w.kz)), shear(permute(p1 - ray.o, w.kx, w.ky, w.kz)),
          shear(permute(p2 - ray.o, w.kx, w.ky, w.kz))};
}

std::optional<TriangleHit> intersectSheared(ShearedTriangle s, const WatertightRay& w, float tMax) {
  return finishSheared(s, w, tMax);
}

}  // namespace glint
