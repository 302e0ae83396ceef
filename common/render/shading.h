#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "common/math/power.h"

namespace glint {

// The thesis's Phong model, term by term (thesis digest, "Lighting"):
//   I   = I_A + sum_i (I_D,i + I_S,i)
//   I_A = C r_A
//   I_D = I_L C r_D (N . L)
//   I_S = I_L r_S (V . R)^h,  R = 2 (N . L) N - L
// N, L, V unit; L towards the light, V towards the viewer.

glm::vec3 phongAmbient(const glm::vec3& c, float rA);
// Zero when the light is behind the surface (N . L <= 0).
inline glm::vec3 phongDiffuse(const glm::vec3& lightI, const glm::vec3& c, float rD, const glm::vec3& n,
                              const glm::vec3& l) {
  const float nl = glm::dot(n, l);
  if (nl <= 0.0f) return glm::vec3(0.0f);
  return lightI * c * (rD * nl);
}
// Zero when N . L <= 0 or V . R <= 0.
inline glm::vec3 phongSpecular(const glm::vec3& lightI, float rS, float h, const glm::vec3& n, const glm::vec3& l,
                               const glm::vec3& v) {
  const float nl = glm::dot(n, l);
  if (nl <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 r = 2.0f * nl * n - l;
  const float vr = glm::dot(v, r);
  if (vr <= 0.0f) return glm::vec3(0.0f);
  return lightI * (rS * power(vr, h));
}
// I_L = color / (c + l d + q d^2) for attenuation (c, l, q) at distance d.
glm::vec3 attenuate(const glm::vec3& color, const glm::vec3& attenuation, float d);
// A spot light's share at unit direction l from the surface towards the
// light (KHR_lights_punctual's falloff): with c the cosine of the angle
// between the light's axis and -l, t = (c - cosOuter) / (cosInner -
// cosOuter) clamped to [0, 1], the share is t^2 (1 inside the inner cone, 0
// outside the outer one; equal cones: a hard edge, the ramp kHardSpotEdge
// wide in cosine).
constexpr float kHardSpotEdge = 1e-4f;
float spotFactor(const glm::vec3& axis, float cosInner, float cosOuter, const glm::vec3& l);

}  // namespace glint
