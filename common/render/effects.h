#pragma once

#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/scene/scene.h"

namespace glint {

// What a material can need from the tracer.
struct MaterialEffects {
  bool direct = false;      // diffuse or specular > 0: lights and shadow rays matter
  bool specular = false;    // specular > 0: the (V . R)^h term
  bool textured = false;    // checker or image texture, or an emission texture: uv lookups
  bool emits = false;       // emission > 0: light of its own
  bool reflects = false;    // a reflected ray can carry at least min_weight
  bool glossy = false;      // reflects, with roughness > 0: the ray drawn from a lobe
  bool refracts = false;    // a refracted ray can carry at least min_weight
};

// Which effects can occur at all in a scene, decided before rendering so the
// tracer does no work (rays, code paths, lookups) for an effect no material,
// light or setting calls for. derive() is exact in one direction: an effect
// it turns off cannot change the image.
struct EffectPlan {
  // shadow rays: lights (and emitting surfaces under path transport), lit
  // materials and a possible occluder
  bool shadows = false;
  bool reflection = false;    // reflected rays
  bool refraction = false;    // refracted rays
  bool textures = false;      // texture lookups other than a solid colour
  bool emission = false;      // a material's light of its own
  bool vertexColors = false;  // a mesh's per-vertex colours
  bool attenuation = false;   // distance fall-off of some light (other than a constant)
  bool antialiasing = false;  // samples off the pixel centre: several, or jittered
  bool softShadows = false;   // shadow rays to points over an area or sphere light, or an emitting surface
  bool depthOfField = false;  // camera rays from points over a thin lens
  bool glossyReflection = false;  // reflected rays drawn from a rough material's lobe
  bool environment = false;       // escaping rays see the environment image, not the background
  // Path transport with bounces, some light (a light, an emitting material,
  // the environment or a background) and a material that scatters it: light
  // that surfaces send one another.
  bool indirectLight = false;
  std::vector<MaterialEffects> materials;
  std::vector<bool> lights;   // false: the light adds nothing (black) and is skipped

  static EffectPlan derive(const Scene& scene, const FrameSettings& frame);
  static EffectPlan derive(const Scene& scene) { return derive(scene, scene.frame); }
};

// The plan's effects by name, in one order: shadows, reflection,
// refraction, textures, emission, vertex_colors, attenuation, antialiasing,
// soft_shadows, depth_of_field, glossy_reflection, environment,
// indirect_light.
struct NamedEffect {
  const char* name;
  bool needed;
};
std::vector<NamedEffect> namedEffects(const EffectPlan& plan);

nlohmann::json toJson(const EffectPlan& plan);

// Whether the raster pass decides shadows: shadows can occur, a point, spot
// or directional light casts them, the mask leaves a lit material to
// OpenGL, and the maps are not turned off (client/raster/shadow_maps.h).
bool rasterShadows(const Scene& scene, const EffectPlan& plan, const MaskSettings& mask);

}  // namespace glint
