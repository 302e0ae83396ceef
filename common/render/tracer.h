#pragma once

#include <glm/vec3.hpp>

#include <optional>
#include <vector>

#include "common/geometry/bvh.h"
#include "common/render/area_light.h"
#include "common/render/bsdf.h"
#include "common/render/effects.h"
#include "common/render/emitter_patches.h"
#include "common/render/emitters.h"
#include "common/render/irradiance_field.h"
#include "common/render/ray_stats.h"
#include "common/scene/scene.h"

namespace glint {

// Whitted back ray tracing (the thesis's RT unit): at each hit, shadow rays
// to the lights and the Phong model, then a reflected and a refracted ray
// weighted by the material. An area or sphere light's shadow rays go to
// points drawn from the camera sample's key (common/render/area_light.h,
// common/render/sphere_light.h), as does a rough material's reflected ray
// (common/render/glossy_lobe.h). Recursion stops at max_depth (primary ray =
// depth 1) or when a ray's path weight would fall below min_weight. Only the
// paths the effect plan allows are run.
//
// With an irradiance field (the hybrid frame under path transport), the
// light other surfaces reflect onto a diffuse surface comes from the field,
// read as the raster reads it, in place of the constant ambient term; the
// light the emitting surfaces send it straight, each triangle's in closed
// form times the share its strata's shadow rays find open
// (common/render/emitter_patches.h) where they are few flat ones, else from
// one point drawn on them a sample (shadowed as a shadow ray finds).
//
// Sidedness comes from the path, not from stored normals: a ray refracted
// into a transparent object is inside it until it refracts out again, so a
// closed mesh renders the same whichever way its triangles are wound.
class Tracer {
 public:
  Tracer(const Scene& scene, const Bvh& bvh, const FrameSettings& frame, const EffectPlan& plan,
         const IrradianceField* field = nullptr);
  // It refers to the scene, BVH and plan it was made with.
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  // Radiance along a primary ray (direction unit length) of the camera
  // sample `key`.
  glm::vec3 radiance(const Ray& ray, const SampleKey& key, RayStats& stats) const;
  // The same with the field's light: none where the field could not decide
  // at a surface the sample reached (its caller traces a path instead).
  std::optional<glm::vec3> radianceWithField(const Ray& ray, const SampleKey& key, RayStats& stats) const;

 private:
  // What the rays of one camera sample share along its path.
  struct Path {
    SampleKey key;
    RayStats& stats;
    bool undecided = false;  // the field could not decide at some surface
  };
  // Where a ray leaves a hit: the surface and the hit it came from, the
  // origin of rays on the side of its geometric normal (shadow and reflected
  // rays), that origin lifted onto the smooth surface once a shadow ray
  // needs it (shadowFrom), the way to the viewer.
  struct ShadingPoint {
    const SurfaceHit& s;
    const Hit& hit;
    glm::vec3 outside;
    mutable std::optional<glm::vec3> lifted;
    glm::vec3 toViewer;
    int depth;
  };
  // A material's colour and terms at a point; with a field, its lobes'
  // weights under path transport (direct light is then the lobes').
  struct Surface {
    glm::vec3 color;
    const Material& m;
    const MaterialEffects& e;
    const LobeWeights* lobes;
  };
  glm::vec3 trace(const Ray& ray, int depth, float weight, bool inside, Path& path) const;
  // The origin of a shadow ray along `d` (from at.outside): at.outside where
  // d leaves the triangle's outer side; where d passes behind the flat
  // triangle (a light its smooth normal still faces), the point lifted onto
  // the smooth surface (Geometry::lifted, computed once a point), so that
  // the triangles around do not shadow it.
  const glm::vec3& shadowFrom(const ShadingPoint& at, const glm::vec3& d) const;
  glm::vec3 shade(const ShadingPoint& at, const Material& m, const MaterialEffects& e, Path& path) const;
  // The light other surfaces send the point: the diffuse albedo (the
  // BSDF's) over pi times the irradiance, the field's and the emitters'.
  glm::vec3 fieldLight(const ShadingPoint& at, const Surface& f, Path& path) const;
  glm::vec3 emitterIrradiance(const ShadingPoint& at, Path& path) const;
  [[gnu::noinline]] glm::vec3 patchIrradiance(const ShadingPoint& at, int patch, Path& path) const;
  // A light at `position` seen from the point: the unit direction and the
  // distance; none when it is behind the surface.
  struct Direction {
    glm::vec3 l;
    float distance;
  };
  // towards to blocked run for each light at each hit: defined inline in
  // tracer.cpp, so that the compiler keeps them in shade's registers.
  std::optional<Direction> towards(const ShadingPoint& at, const glm::vec3& position) const;
  // d, unless the light comes from behind the surface.
  std::optional<Direction> facing(const ShadingPoint& at, const Direction& d) const;
  // Adds the diffuse and specular light of intensity lightI from d: the
  // thesis's Phong, or with a field path transport's lobes (lobesReflect),
  // so that a pixel the field lights agrees with the path trace.
  void addPhong(const ShadingPoint& at, const Surface& f, const Direction& d, const glm::vec3& lightI,
                glm::vec3& result) const;
  // A point, spot or directional light: one shadow ray.
  void addPunctualLight(const ShadingPoint& at, const Surface& f, int light, Path& path, glm::vec3& result) const;
  // Whether the shadow ray from the point to the light (to infinity for a
  // directional light) is blocked.
  bool blocked(const ShadingPoint& at, const Light& l, Path& path) const;
  // The soft lights, kept out of line: inlined, they would make the
  // shading point and surface they take by reference live in memory on every
  // hit, and the point lights' path would pay for lights a scene may not
  // have (and, inlined in trace, crowd out the inlining of its hot calls).
  [[gnu::noinline]] void addAreaLight(const ShadingPoint& at, const Surface& f, int light, Path& path,
                                      glm::vec3& result) const;
  [[gnu::noinline]] void addSphereLight(const ShadingPoint& at, const Surface& f, int light, Path& path,
                                        glm::vec3& result) const;
  // The share of a soft light's unshadowed light that reaches the point: one
  // shadow ray for each of `count` strata, to target(k, u) (none: the
  // stratum's point gives nothing; u from the key's dimensions from
  // `first` on, two a stratum), its verdict weighted by weight(direction,
  // cosine), what the point gives a diffuse surface.
  template <typename Target, typename Weight>
  float visibleShare(const ShadingPoint& at, int first, int count, Path& path, const Target& target,
                     const Weight& weight) const;
  // The sample key's dimensions (SampleKey): from kFirstLightDimension, for
  // each depth, each soft light's two per stratum, then each emitter patch's;
  // after max_depth such blocks, two per depth for a glossy reflection's lobe.
  // A soft light's or patch's first, `offset` into its depth's block.
  int lightDimension(int depth, int offset) const;
  int lobeDimension(int depth) const;
  // The mirror direction, or a rough material's drawn from its lobe.
  glm::vec3 reflectedDirection(const Ray& ray, const ShadingPoint& at, const Material& m, const MaterialEffects& e,
                               const Path& path) const;
  glm::vec3 lightIntensity(const glm::vec3& color, const glm::vec3& attenuation, float distance) const;
  // The surface's own light at uv (Material::emission).
  glm::vec3 emitted(const Material& m, const glm::vec2& uv) const;

  const Scene& scene_;
  const Bvh& bvh_;
  TracingSettings tracing_;
  const EffectPlan& plan_;
  const Environment* environment_;                     // what escaping rays see; none: the background
  const IrradianceField* field_;                       // none: the ambient term
  std::optional<EmitterPatches> patches_;              // with a field, where the emitters are few flat ones
  std::optional<Emitters> emitters_;                   // with a field, where they are not
  std::vector<int> patchDimensions_;                   // per patch: its first dimension in a depth's block
  std::vector<std::optional<AreaLightPoints>> areas_;  // per light: an area light's points
  std::vector<std::vector<Stratum>> sphereStrata_;     // per light: a sphere light's strata
  std::vector<int> lightDimensions_;                   // per light: its first dimension in a depth's block
  int lightDimensionsPerDepth_ = 0;
};

}  // namespace glint
