#include "common/bounds.h"

#include <cmath>

#include "common/float_bits.h"

namespace glint {

float Bounds3::surfaceArea() const {
  if (empty()) return 0.0f;
  const glm::vec3 e = extent();
  return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
}

int Bounds3::longestAxis() const {
  const glm::vec3 e = extent();
  if (e.x >= e.y && e.x >= e.z) return 0;
  return e.y >= e.z ? 1 : 2;
}

bool intersectSlabs(const Bounds3& b, const Ray& ray, float tMin, float tMax, SlabHit* hit) {
  float t0 = tMin;
  float t1 = tMax;
  for (int axis = 0; axis < 3; ++axis) {
    // The sign bit of 1/d (also of -0.0 -> -inf) picks the near plane.
    const bool negative = std::signbit(ray.invD[axis]);
    const float nearPlane = negative ? b.max[axis] : b.min[axis];
    const float farPlane = negative ? b.min[axis] : b.max[axis];
    const float tNear = (nearPlane - ray.o[axis]) * ray.invD[axis];
    float tFar = (farPlane - ray.o[axis]) * ray.invD[axis];
    tFar *= 1.0f + 2.0f * gamma(3);
    // Written so that a NaN comparison is false and leaves t0 / t1 unchanged.
    t0 = tNear > t0 ? tNear : t0;
    t1 = tFar < t1 ? tFar : t1;
    if (t0 > t1) return false;
  }
  if (hit) *hit = {t0, t1};
  return true;
}

}  // namespace glint
