#pragma once

#include <cstdint>
#include <optional>

#include <glm/vec3.hpp>

#include "common/geometry/bounds.h"
#include "common/geometry/ray.h"

namespace glint {

struct Sphere {
  glm::vec3 centre{0.0f};
  float radius = 1.0f;
  std::uint32_t material = 0;

  Bounds3 bounds() const { return {centre - glm::vec3(radius), centre + glm::vec3(radius)}; }
};

// Nearest root t of |o + t d - c| = r with 0 < t < tMax, for unit d.
// Follows Haines et al., Ray Tracing Gems chapter 7: the discriminant is
// formed as r^2 - |f + b d|^2 (no cancellation for small spheres far away),
// and the roots as c/q and q with q = b + sign(b) sqrt(disc) (no cancellation
// between b and the square root). From inside, the near root is negative and
// the far one is returned.
std::optional<float> intersectSphere(const Sphere& s, const Ray& ray, float tMax);

// The point of the sphere nearest to p: projects a computed hit point back
// onto the surface, which removes most of the error of o + t d.
glm::vec3 projectToSphere(const Sphere& s, const glm::vec3& p);

}  // namespace glint
