#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "common/geometry/bvh.h"
#include "common/geometry/region_query.h"
#include "common/render/effects.h"
#include "common/scene/scene.h"

namespace glint::gl {

// Which pixels of a raster frame see every area light whole, proved from the
// scene's geometry: the raster shades an area light's unshadowed light
// (common/render/area_light.h), which is the tracer's value wherever nothing
// stands between the point and any point of the light. For a pixel's point p
// (from its depth), lifted off its surface towards the light by 1/1000 of
// its distances to the eye and the light, nothing may enter the pyramid from
// p to the light's parallelogram (common/geometry/region_query.h, then each
// primitive it finds by separating axes); a pixel
// not proved so is traced, the penumbra and the umbra alike. A point behind
// a light's plane gets nothing from it and needs no proof.
class PenumbraProof {
 public:
  // For the area lights the plan lets cast shadows (none: active() false).
  PenumbraProof(const Scene& scene, const EffectPlan& plan);
  bool active() const { return !lights_.empty(); }

  // Whether every area light reaches the whole of p's view of it.
  bool seesWhole(const glm::vec3& p, const glm::vec3& eye) const;

 private:
  // Whether a primitive the region query found may enter the pyramid (an
  // exact separating-axis test; the query's answer is conservative).
  bool blocks(std::uint32_t prim, const ConvexRegion& pyramid) const;
  struct Parallelogram {
    glm::vec3 corners[4];
    glm::vec3 centre;
    glm::vec3 normal;  // unit, towards the lit side
  };
  const Geometry& geometry_;
  std::vector<Parallelogram> lights_;
  Bvh bvh_;
};

}  // namespace glint::gl
