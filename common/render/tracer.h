#pragma once

#include <glm/vec3.hpp>

#include "common/geometry/bvh.h"
#include "common/render/effects.h"
#include "common/render/ray_stats.h"
#include "common/scene/scene.h"

namespace glint {

// Whitted back ray tracing (the thesis's RT unit): at each hit, shadow rays
// to the point lights and the Phong model, then a reflected and a refracted
// ray weighted by the material. Recursion stops at max_depth (primary ray =
// depth 1) or when a ray's path weight would fall below min_weight. Only the
// paths the effect plan allows are run.
//
// Sidedness comes from the path, not from stored normals: a ray refracted
// into a transparent object is inside it until it refracts out again, so a
// closed mesh renders the same whichever way its triangles are wound.
class Tracer {
 public:
  Tracer(const Scene& scene, const Bvh& bvh, const TracingSettings& tracing, const EffectPlan& plan);
  // It refers to the scene, BVH and plan it was made with.
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  // Radiance along a primary ray (direction unit length).
  glm::vec3 radiance(const Ray& ray, RayStats& stats) const;

 private:
  glm::vec3 trace(const Ray& ray, int depth, float weight, bool inside, RayStats& stats) const;
  // `outside` is the origin of rays leaving s on the side of its geometric
  // normal (shadow and reflected rays).
  glm::vec3 shade(const SurfaceHit& s, const glm::vec3& outside, const glm::vec3& toViewer, const Material& m,
                  const MaterialEffects& e, RayStats& stats) const;
  glm::vec3 lightIntensity(int light, float distance) const;
  // The surface's own light at uv (Material::emission).
  glm::vec3 emitted(const Material& m, const glm::vec2& uv) const;

  const Scene& scene_;
  const Bvh& bvh_;
  TracingSettings tracing_;
  const EffectPlan& plan_;
};

}  // namespace glint
