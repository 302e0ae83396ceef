#pragma once

#include <cmath>
#include <optional>

#include <glm/gtc/type_ptr.hpp>
#include <glm/vec3.hpp>

#include "common/geometry/ray.h"

namespace glint {

// Hit of a ray with triangle (p0, p1, p2): distance and barycentric weights of
// the three vertices (b0 + b1 + b2 = 1, all >= 0).
struct TriangleHit {
  float t;
  float b0;
  float b1;
  float b2;
};

// Watertight ray/triangle intersection (Woop, Benthin and Wald 2013,
// "Watertight Ray/Triangle Intersection", JCGT 2(1); the variant of pbrt-v4
// 6.5.3). The vertices are translated to the ray origin, permuted so the
// ray's dominant axis is z, and sheared so the ray becomes +z; the edge
// functions are then 2D and computed in the same way for both triangles of a
// shared edge, so a ray through the edge hits at least one of them. Edge
// functions that come out exactly zero are recomputed in double. Accepts both
// windings; t is checked against a conservative error bound, so t > 0.
std::optional<TriangleHit> intersectTriangle(const Ray& ray, const glm::vec3& p0,
                                             const glm::vec3& p1, const glm::vec3& p2, float tMax);

// The per-ray part of the test (axis permutation and shear), computed once
// per ray when the ray meets many triangles.
// Inline and without branches on the direction: it is made for every ray,
// whose directions a branch predictor cannot guess.
struct WatertightRay {
  int kx, ky, kz;
  float sx, sy, sz;
  explicit WatertightRay(const Ray& ray) {
    const float x = std::abs(ray.d.x), y = std::abs(ray.d.y), z = std::abs(ray.d.z);
    const int yz = y > z ? 1 : 2;
    kz = x > y && x > z ? 0 : yz;  // the dominant axis
    kx = kz == 2 ? 0 : kz + 1;
    ky = kx == 2 ? 0 : kx + 1;
    const float* d = glm::value_ptr(ray.d);
    sx = -d[kx] / d[kz];
    sy = -d[ky] / d[kz];
    sz = glm::value_ptr(ray.invD)[kz];  // 1 / d.z, already computed
  }
};
std::optional<TriangleHit> intersectTriangle(const Ray& ray, const WatertightRay& w, const glm::vec3& p0,
                                             const glm::vec3& p1, const glm::vec3& p2, float tMax);

// The test in its two steps (intersectTriangle is the second applied to the
// first). A triangle in the ray's frame: the vertices translated to the ray
// origin, permuted so that the ray's dominant axis is z, x and y sheared so
// that the ray runs along z (z itself not yet scaled).
struct ShearedTriangle {
  glm::vec3 a, b, c;
};
ShearedTriangle shearTriangle(const Ray& ray, const WatertightRay& w, const glm::vec3& p0, const glm::vec3& p1,
                              const glm::vec3& p2);
// The edge functions (in double where one comes out zero), the inside test,
// the distance and its error bound.
std::optional<TriangleHit> intersectSheared(ShearedTriangle s, const WatertightRay& w, float tMax);

}  // namespace glint
