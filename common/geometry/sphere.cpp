#include "common/geometry/sphere.h"

#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

namespace glint {

std::optional<float> intersectSphere(const Sphere& s, const Ray& ray, float tMax) {
  const glm::vec3 f = ray.o - s.centre;
  const float b = -glm::dot(f, ray.d);
  const glm::vec3 l = f + b * ray.d;  // centre to the ray's closest approach
  const float r2 = s.radius * s.radius;
  const float disc = r2 - glm::dot(l, l);
  if (!(disc >= 0.0f)) return std::nullopt;
  const float c = glm::dot(f, f) - r2;
  const float q = b + std::copysign(std::sqrt(disc), b);
  if (q == 0.0f) return std::nullopt;  // tangent ray starting on the sphere
  float t0 = c / q;
  float t1 = q;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > 0.0f && t0 < tMax) return t0;
  if (t1 > 0.0f && t1 < tMax) return t1;
  return std::nullopt;
}

glm::vec3 projectToSphere(const Sphere& s, const glm::vec3& p) {
  const glm::vec3 v = p - s.centre;
  const float len = glm::length(v);
  if (!(len > 0.0f)) return p;
  return s.centre + v * (s.radius / len);
}

}  // namespace glint
