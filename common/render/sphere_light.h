#pragma once

#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/render/sampling.h"

namespace glint {

// A sphere light as one point sees it: the cone of directions from the point
// to the ball. Its shadow rays go to the ball's near side, uniformly in solid
// angle over the cone: the unit square (x, y) of a stratum's point maps to
// the polar angle's cosine 1 - x (1 - cos theta_max) and the azimuth 2 pi y,
// so equal strata of the square are equal solid angles. Each ray's verdict
// is weighted by the cosine at the receiving surface (the ball's radiance is
// the same in every direction of the cone), the ratio estimator of an area
// light (common/render/area_light.h); the unshadowed light is a point
// light's at the centre, which is exact for a diffuse surface that sees the
// whole ball above its horizon.
class SphereLightView {
 public:
  // None when the point lies in the ball, or the numbers are not finite.
  static std::optional<SphereLightView> from(const glm::vec3& centre, float radius, const glm::vec3& p);

  struct Sample {
    glm::vec3 direction;  // unit, from the point
    float distance;       // to the ball's surface along it
  };
  // The direction at fraction u of stratum s.
  Sample sample(const Stratum& s, const glm::vec2& u) const;
  // The cone's solid angle, 2 pi (1 - cos theta_max): sample() draws
  // directions with density 1 / solidAngle().
  float solidAngle() const { return 6.283185307179586f * oneMinusCos_; }

 private:
  SphereLightView(const glm::vec3& axis, float distance, float sin2Max);
  glm::vec3 axis_;     // unit, to the centre
  glm::vec3 t_, b_;    // completing the axis to an orthonormal basis
  float distance_;     // to the centre
  float sin2Max_;      // sin^2 of the cone's half-angle: (radius / distance)^2
  float oneMinusCos_;  // 1 - cos of the cone's half-angle
};

}  // namespace glint
