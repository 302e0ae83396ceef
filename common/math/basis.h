#pragma once

#include <cmath>

#include <glm/vec3.hpp>

namespace glint {

// Two unit vectors t and b completing unit n to a right-handed orthonormal
// basis (t, b, n), continuous except where n.z changes sign (Duff et al.,
// "Building an Orthonormal Basis, Revisited", JCGT 2017).
inline void orthonormalBasis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

}  // namespace glint
