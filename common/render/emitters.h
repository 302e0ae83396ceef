#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/geometry/geometry.h"
#include "common/render/effects.h"
#include "common/scene/scene.h"

namespace glint {

// The scene's emitting surfaces (every triangle and sphere whose material
// has an emission) as one light for path transport and for the tracer that
// reads an irradiance field (which holds no emission): a point drawn uniformly
// by area over all of them, so that its density is 1 / area() wherever it
// lands.
class Emitters {
 public:
  Emitters(const Geometry& geometry, const EffectPlan& plan);

  bool empty() const { return prims_.empty(); }
  float area() const { return total_; }

  // A point on an emitter, the emitter's unit normal there (either side),
  // and how to find the point again: the primitive and the point's
  // barycentrics on a triangle (b0 = 1 - b1 - b2; 0 on a sphere).
  struct Point {
    glm::vec3 p, n;
    std::uint32_t prim;
    float b1, b2;
  };
  // pickAndPlace.x chooses the primitive (by area) and, rescaled within
  // that primitive's share, places the point on it with pickAndPlace.y: a
  // set of values spread evenly over the square stays spread evenly over
  // the emitters' whole area.
  Point sample(const glm::vec2& pickAndPlace) const;

  // A point drawn on the emitters (sample()'s) as seen from p: the unit
  // direction toward it, the distance a shadow ray goes (kShortOfEmitter
  // short of it, so that the emitter does not block it), the radiance it
  // sends p and the direction's density (solid angle); none where it sends
  // p nothing.
  struct Seen {
    glm::vec3 wi;
    float distance;
    glm::vec3 radiance;
    float pdf;
  };
  std::optional<Seen> seenFrom(const Scene& scene, const EffectPlan& plan, const glm::vec3& p,
                               const glm::vec2& pickAndPlace) const;
  static constexpr float kShortOfEmitter = 1e-3f;

 private:
  const Geometry& geometry_;
  std::vector<std::uint32_t> prims_;
  std::vector<float> cumulative_;  // areas summed up to and including each primitive
  float total_ = 0.0f;
};

}  // namespace glint
