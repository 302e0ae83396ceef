#include "common/render/shading.h"

#include <algorithm>

#include <glm/geometric.hpp>

namespace glint {

glm::vec3 phongAmbient(const glm::vec3& c, float rA) { return c * rA; }

glm::vec3 attenuate(const glm::vec3& color, const glm::vec3& attenuation, float d) {
  return color / (attenuation.x + attenuation.y * d + attenuation.z * d * d);
}

float spotFactor(const glm::vec3& axis, float cosInner, float cosOuter, const glm::vec3& l) {
  const float c = -glm::dot(axis, l);
  const float t = std::clamp((c - cosOuter) / std::max(cosInner - cosOuter, kHardSpotEdge), 0.0f, 1.0f);
  return t * t;
}

}  // namespace glint
