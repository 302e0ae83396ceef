#include "common/geometry/bounds.h"

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

}  // namespace glint
