#include "common/render/sphere_light.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "common/math/basis.h"
#include "common/math/circular.h"

namespace glint {
namespace {

constexpr float kTwoPi = 6.283185307179586f;

}  // namespace

std::optional<SphereLightView> SphereLightView::from(const glm::vec3& centre, float radius, const glm::vec3& p) {
  const glm::vec3 toCentre = centre - p;
  const float distance = glm::length(toCentre);
  if (!std::isfinite(distance) || !(distance > radius)) return std::nullopt;
  const float ratio = radius / distance;
  return SphereLightView(toCentre / distance, distance, ratio * ratio);
}

SphereLightView::SphereLightView(const glm::vec3& axis, float distance, float sin2Max)
    : axis_(axis),
      distance_(distance),
      sin2Max_(sin2Max),
      // 1 - cos, without the cancellation of a small cone.
      oneMinusCos_(sin2Max / (1.0f + std::sqrt(1.0f - sin2Max))) {
  orthonormalBasis(axis_, t_, b_);
}

SphereLightView::Sample SphereLightView::sample(const Stratum& s, const glm::vec2& u) const {
  const glm::vec2 xy = stratumPoint(s, u);
  const float m = xy.x * oneMinusCos_;  // 1 - cos theta
  const float cosTheta = 1.0f - m;
  const float sinTheta = std::sqrt(m * (2.0f - m));
  const SineCosine phi = sineCosine(kTwoPi * xy.y);
  const glm::vec3 d = glm::normalize(sinTheta * phi.cos * t_ + sinTheta * phi.sin * b_ + cosTheta * axis_);
  // The ray meets the ball where its distance from the centre, in units of
  // the distance to the centre, falls to the radius's share.
  const float along = glm::dot(d, axis_);
  const glm::vec3 off = axis_ - along * d;
  const float inside = std::sqrt(std::max(0.0f, sin2Max_ - glm::dot(off, off)));
  return {d, distance_ * (along - inside)};
}

}  // namespace glint
