#pragma once

#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "common/geometry/bvh.h"
#include "common/render/area_light.h"
#include "common/render/bsdf.h"
#include "common/render/effects.h"
#include "common/render/emitters.h"
#include "common/render/environment_light.h"
#include "common/render/ray_stats.h"
#include "common/render/sampling.h"
#include "common/scene/scene.h"

namespace glint {

// Path transport: unbiased Monte Carlo estimates of the light arriving along
// a camera ray, the light every surface sends every other included. At each
// surface the path hits, light is sampled (next-event estimation: one shadow
// ray to each light, one to a point on the scene's emitting surfaces) and the
// path goes on in a direction drawn from the material's BSDF (bsdf.h); an
// area, sphere or emitting surface found either way is weighted by multiple
// importance sampling with the power heuristic (Veach 1997), so that each
// light is counted once. After kRouletteFrom bounces a path continues with
// the probability of its throughput's largest channel (at most 0.95, Russian
// roulette), and it stops after tracing.maxBounces bounces. Every random
// number comes from the camera sample's key, so the estimate depends on the
// pixel and sample alone: each choice's pair of numbers from the key's
// scrambled Sobol points (SampleKey::stratified), so that a pixel's samples
// spread evenly over each light, lobe and direction.
//
// The lights as radiometry (docs/scene-format.md): a point or spot light of
// `color` has the intensity pi color / attenuation(d) (a diffuse surface it
// lights is as bright as under Whitted transport), a directional light the
// irradiance pi color; an area light is a one-sided Lambertian emitter of
// radiance pi color / area, a sphere light one of radiance color / radius^2
// (as bright as the point light at its centre, from far away), both fading
// with distance as geometry says (their attenuation is a Whitted setting).
// Lights are not seen by camera rays (as under Whitted); rays that bounce see
// them. A material's emission is radiance, on both sides. The environment
// image is a light sampled by its luminance (environment_light.h); the
// background lights the scene through the paths that escape it.
class PathTracer {
 public:
  static constexpr int kRouletteFrom = 3;

  // `sky`: the environment image as a light, nullptr where it has none or
  // the plan does not look it up.
  PathTracer(const Scene& scene, const Bvh& bvh, const EnvironmentLight* sky, const FrameSettings& frame,
             const EffectPlan& plan);
  PathTracer(const PathTracer&) = delete;
  PathTracer& operator=(const PathTracer&) = delete;

  // What the first surface a ray meets adds: its emission and what it
  // reflects (a camera ray's), or what it reflects alone (an irradiance
  // probe's, field_probes.h: the point the field lights samples the
  // emitters itself). `firstDistance`, where given, is set to the first
  // surface's distance along the ray (kInfinity: none), which a probe's
  // visibility map keeps.
  enum class First { kSeen, kReflected };
  glm::vec3 radiance(const Ray& ray, const SampleKey& key, RayStats& stats, First first = First::kSeen,
                     float* firstDistance = nullptr) const;

 private:
  // A surface the path found.
  struct Vertex {
    const SurfaceHit& s;
    const Hit& hit;
    glm::vec3 outside;  // origin of rays leaving on the viewer's side
    mutable std::optional<glm::vec3> lifted;  // shadowFrom's, once a shadow ray needs it
  };
  // The light sampled toward one light: direction, distance, what arrives
  // (the radiance, or for a delta light pi times its intensity at the
  // point) and the direction's density (0 for a delta light).
  struct LightSample {
    glm::vec3 wi;
    float distance;
    glm::vec3 arriving;
    float pdf;
  };
  // Next-event estimation at v: each light's and the emitters' share,
  // weighted against the BSDF's direction unless the path ends here (`last`).
  glm::vec3 directLight(const Vertex& v, const Bsdf& bsdf, const SampleKey& key, int bounce, bool last,
                        RayStats& stats) const;
  std::optional<LightSample> sampleLight(const Vertex& v, int light, const glm::vec2& u) const;
  glm::vec3 contribution(const Vertex& v, const Bsdf& bsdf, const LightSample& l, bool last, RayStats& stats) const;
  // Area and sphere lights a bounced ray meets before tMax, weighted against
  // light sampling for a ray drawn with density bsdfPdf (0: a delta lobe).
  glm::vec3 lightsAlong(const Ray& ray, float tMax, float bsdfPdf) const;
  // A surface's own radiance at a hit, weighted likewise.
  glm::vec3 emittedAt(const Ray& ray, const Hit& hit, const SurfaceHit& s, const Material& m, float bsdfPdf,
                      bool weigh) const;
  // What a ray that leaves the scene sees, weighted against sampling the
  // environment for a ray drawn with density bsdfPdf (0: not weighed).
  glm::vec3 escaped(const glm::vec3& d, float bsdfPdf) const;
  // The origin of a shadow ray along d: the outside offset, or where d
  // passes behind the flat triangle, the point lifted onto the smooth
  // surface (the shadow terminator, as Tracer does), computed once a vertex.
  const glm::vec3& shadowFrom(const Vertex& v, const glm::vec3& d) const;
  int pair(int bounce, int offset) const { return SampleKey::kFirstPathPair + bounce * perBounce_ + offset; }

  const Scene& scene_;
  const Bvh& bvh_;
  const EffectPlan& plan_;
  int maxBounces_;
  Emitters emitters_;
  const EnvironmentLight* sky_;  // the environment image, where it has light and the plan looks it up
  std::vector<float> lightArea_;  // per light: an area light's area, else 0
  int perBounce_;                     // pairs of sample dimensions one bounce draws
};

}  // namespace glint
