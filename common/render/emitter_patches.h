#pragma once

#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/render/effects.h"
#include "common/render/sampling.h"
#include "common/scene/scene.h"

namespace glint {

// The emitting triangles of a scene lit by an irradiance field, which the
// tracer and the raster share (the field holds no emission: the light
// emitters send a point directly is the shading point's own):
//  - the unshadowed irradiance at a point is each triangle's in closed form
//    (shading.glsl's triangleIrradiance: exact, from both sides), which the
//    raster shades;
//  - the share of it that arrives is measured with one shadow ray to a
//    point jittered in each of the triangle's equal-area strata
//    (jitteredStratum over the unit square, carried onto the triangle by
//    the map that draws points uniformly on it), the ratio estimator of
//    area lights (common/render/area_light.h): a point every ray reaches
//    gets exactly the unshadowed value, so only the penumbra is noisy.
// Only a few flat emitters of plain emission are patches: a scene with more
// than kMaxPatches emitting triangles, an emitting sphere or an emission
// texture has none (the tracer then draws points on the emitters at random,
// and the raster cannot draw their light).
class EmitterPatches {
 public:
  static constexpr int kMaxPatches = 16;
  static constexpr int kDefaultPoints = 16;  // all patches together, unless light_samples says

  struct Patch {
    glm::vec3 corner, edge1, edge2;  // the triangle: corner, corner + edge1, corner + edge2
    glm::vec3 normal;                // unit, the triangle's face normal
    glm::vec3 radiance;              // the emission
    float area = 0.0f;
    std::vector<Stratum> strata;
    // The point at (s, t) of the unit square, uniform by area.
    glm::vec3 at(const glm::vec2& st) const;
    // What the triangle sends a point p with unit normal n, unshadowed.
    glm::vec3 irradianceAt(const glm::vec3& p, const glm::vec3& n) const;
  };

  // The scene's patches (none where the plan has no emission; no answer
  // where the emitters are not few flat plain ones); `points` strata in all
  // (0: the default), shared by area, at least one a patch.
  static std::optional<EmitterPatches> of(const Scene& scene, const EffectPlan& plan, int points);

  const std::vector<Patch>& patches() const { return patches_; }
  int points() const;  // strata over all patches

 private:
  std::vector<Patch> patches_;
};

}  // namespace glint
