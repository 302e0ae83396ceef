#pragma once

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/render/sampling.h"
#include "common/scene/light.h"

namespace glint {

// Where an area light's points lie, the same for the tracer and the raster.
// Its parallelogram is cut into `count` equal-area strata (jitteredStratum
// over the (s, t) square, the point position + (s - 1/2) u + (t - 1/2) v):
//  - the unshadowed light at a point is the sum over the strata's centres,
//    each a point light of color / count: the raster shades exactly this;
//  - the share of it that arrives is measured with one shadow ray to a
//    point jittered in each stratum (its place drawn from the camera sample's
//    key), each weighted by what the point would give a diffuse surface: a
//    point every ray reaches is lit by exactly the unshadowed value, so only
//    the penumbra is noisy (the ratio estimator of Heitz, Hill and McGuire,
//    "Combining analytic direct illumination and stochastic shadows", 2018).
struct AreaLightPoints {
  std::vector<glm::vec3> centres;
  std::vector<Stratum> strata;
  glm::vec3 color{0.0f};   // each point's: the light's color / count
  glm::vec3 normal{0.0f};  // unit, towards the lit side

  AreaLightPoints(const Light& light, int count);
  // Stratum k's point at fraction u of it.
  glm::vec3 jittered(int k, const glm::vec2& u) const;
  // Whether a point light at `point` lights `p` (p on the lit side).
  bool lights(const glm::vec3& point, const glm::vec3& p) const;

 private:
  glm::vec3 corner_;  // the (s, t) = (0, 0) corner
  glm::vec3 u_, v_;
};

}  // namespace glint
