#include "common/render/shading.h"

#include <algorithm>

#include <glm/geometric.hpp>

#include "common/math/power.h"

namespace glint {

glm::vec3 phongAmbient(const glm::vec3& c, float rA) { return c * rA; }

glm::vec3 phongDiffuse(const glm::vec3& lightI, const glm::vec3& c, float rD, const glm::vec3& n,
                       const glm::vec3& l) {
  const float nl = glm::dot(n, l);
  if (nl <= 0.0f) return glm::vec3(0.0f);
  return lightI * c * (rD * nl);
}

glm::vec3 phongSpecular(const glm::vec3& lightI, float rS, float h, const glm::vec3& n,
                        const glm::vec3& l, const glm::vec3& v) {
  const float nl = glm::dot(n, l);
  if (nl <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 r = 2.0f * nl * n - l;
  const float vr = glm::dot(v, r);
  if (vr <= 0.0f) return glm::vec3(0.0f);
  return lightI * (rS * power(vr, h));
}

glm::vec3 attenuate(const glm::vec3& color, const glm::vec3& attenuation, float d) {
  return color / (attenuation.x + attenuation.y * d + attenuation.z * d * d);
}

float spotFactor(const glm::vec3& axis, float cosInner, float cosOuter, const glm::vec3& l) {
  const float c = -glm::dot(axis, l);
  const float t = std::clamp((c - cosOuter) / std::max(cosInner - cosOuter, kHardSpotEdge), 0.0f, 1.0f);
  return t * t;
}

}  // namespace glint
