#include "common/render/glossy_lobe.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "common/math/basis.h"
#include "common/math/circular.h"
#include "common/render/optics.h"

namespace glint {
namespace {

constexpr float kTwoPi = 6.283185307179586f;

}  // namespace

glm::vec3 ggxMicrofacetNormal(const glm::vec3& n, float alpha, const glm::vec2& u) {
  // tan^2 theta = alpha^2 u / (1 - u), as cos^2 theta to keep it finite at u -> 1.
  const float cos2 = (1.0f - u.x) / (1.0f + (alpha * alpha - 1.0f) * u.x);
  const float cosTheta = std::sqrt(cos2);
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cos2));
  const SineCosine phi = sineCosine(kTwoPi * u.y);
  glm::vec3 t, b;
  orthonormalBasis(n, t, b);
  return glm::normalize(sinTheta * phi.cos * t + sinTheta * phi.sin * b + cosTheta * n);
}

glm::vec3 glossyDirection(const glm::vec3& d, const glm::vec3& ns, const glm::vec3& ng, float roughness,
                          const glm::vec2& u) {
  const glm::vec3 r = reflect(d, ggxMicrofacetNormal(ns, roughness * roughness, u));
  const float below = glm::dot(r, ng);
  return below > 0.0f ? r : glm::normalize(r - 2.0f * below * ng);
}

}  // namespace glint
