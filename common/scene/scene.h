#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "common/scene/camera.h"
#include "common/base/enum_words.h"
#include "common/geometry/geometry.h"
#include "common/image/output_settings.h"
#include "common/scene/environment.h"
#include "common/scene/light.h"
#include "common/scene/material.h"
#include "common/scene/texture.h"

namespace glint {

// kAdaptive: one sample per pixel, then the jittered pattern's full count
// where the pixel differs from a neighbour by more than adaptiveThreshold.
// kPerceptual: one ray at each pixel's centre, then the jittered pattern's
// full count where it differs visibly from one of its eight neighbours'
// (FLIP's colour term above perceptualThreshold). kSobol: a scrambled Sobol
// sequence over the pixel (common/render/sobol.h), stratified in every
// shape at power-of-two counts.
enum class SamplePattern { kRegular, kJittered, kAdaptive, kPerceptual, kSobol };
enum class FilterType { kBox, kTent, kGaussian, kMitchell };
// kPerceptual: auto's pixels, traced with the perceptual pattern, and the
// raster's pixels on a visible edge of its colours (client/raster/hybrid_frame.h).
enum class MaskRule { kAuto, kAll, kNone, kPerceptual };
// How light is carried: kWhitted, the thesis's tracer (direct light from
// the lights, mirror and refracted rays, a constant ambient term for the
// rest); kPath, Monte Carlo path tracing of the light every surface sends
// every other (common/render/path_tracer.h).
enum class Transport { kWhitted, kPath };

template <>
struct EnumWords<SamplePattern> {
  static constexpr std::array<std::pair<SamplePattern, std::string_view>, 5> kWords{
      {{SamplePattern::kRegular, "regular"},
       {SamplePattern::kJittered, "jittered"},
       {SamplePattern::kAdaptive, "adaptive"},
       {SamplePattern::kPerceptual, "perceptual"},
       {SamplePattern::kSobol, "sobol"}}};
};
template <>
struct EnumWords<FilterType> {
  static constexpr std::array<std::pair<FilterType, std::string_view>, 4> kWords{{{FilterType::kBox, "box"},
                                                                                  {FilterType::kTent, "tent"},
                                                                                  {FilterType::kGaussian, "gaussian"},
                                                                                  {FilterType::kMitchell, "mitchell"}}};
};
template <>
struct EnumWords<Transport> {
  static constexpr std::array<std::pair<Transport, std::string_view>, 2> kWords{
      {{Transport::kWhitted, "whitted"}, {Transport::kPath, "path"}}};
};
template <>
struct EnumWords<MaskRule> {
  static constexpr std::array<std::pair<MaskRule, std::string_view>, 4> kWords{
      {{MaskRule::kAuto, "auto"}, {MaskRule::kAll, "all"}, {MaskRule::kNone, "none"}, {MaskRule::kPerceptual, "perceptual"}}};
};

struct SamplingSettings {
  SamplePattern pattern = SamplePattern::kRegular;
  int samples = 1;
  FilterType filter = FilterType::kBox;
  std::uint32_t seed = 0;
  float adaptiveThreshold = 1.0f / 64.0f;  // per channel, linear; adaptive pattern only
  // A visible difference: FLIP's colour term (0 none, 1 the most) of two
  // displayed colours; the perceptual pattern and mask rule only.
  float perceptualThreshold = 0.3f;
  // Points an area light takes per shadow query; 0: each light's own samples.
  int lightSamples = 0;
};

// How dense the irradiance field is (common/render/irradiance_field.h): the
// indirect light the hybrid frame reads under path transport.
struct FieldSettings {
  static constexpr int kMinProbes = 2;
  static constexpr int kMaxProbes = 64;
  static constexpr int kMinRays = 64;  // one a visibility texel
  static constexpr int kMaxRays = 4096;

  int probes = 8;   // along the scene's longest side; the others in proportion, at least kMinProbes
  int rays = 256;   // a probe's, a power of two from kMinRays to kMaxRays

  // Why a count of rays cannot be (out of range, or not a power of two, as
  // each visibility texel gets as many); none when it can.
  static std::optional<std::string> raysProblem(int rays) {
    if (rays < kMinRays || rays > kMaxRays || (rays & (rays - 1)) != 0) {
      return "must be a power of two from " + std::to_string(kMinRays) + " to " + std::to_string(kMaxRays) +
             " (64, 128, 256 ...): each visibility texel gets as many rays";
    }
    return std::nullopt;
  }
};

struct TracingSettings {
  int maxDepth = 5;         // primary ray = depth 1 (Whitted)
  float minWeight = 0.01f;  // rays whose path weight falls below this are not traced (Whitted)
  Transport transport = Transport::kWhitted;
  int maxBounces = 8;  // path: surfaces a path may bounce off after the first one it hits
  // Path: the hybrid frame draws the light between surfaces from an
  // irradiance field of these settings; none: every pixel is traced.
  std::optional<FieldSettings> field;
};

struct MaskSettings {
  static constexpr int kMaxShadowMap = 4096;
  MaskRule rule = MaskRule::kAuto;
  float minReflectivity = 0.2f;
  float minTransparency = 0.0f;
  // Texels along a shadow map's face edge (client/raster/shadow_maps.h), 0: surfaces
  // OpenGL draws get no shadows (the thesis's frame).
  int shadowMap = 1024;
};

// What may change from one frame of a scene to the next: the view and the
// accuracy settings. The scene file gives the first frame's.
struct FrameSettings {
  int width = 640;
  int height = 480;
  CameraSpec camera;
  SamplingSettings sampling;
  TracingSettings tracing;
  OutputSettings output;
};

// A loaded scene: everything the scene file says, with names resolved to
// indices and every object turned into primitives.
struct Scene {
  FrameSettings frame;  // the first frame's view and accuracy settings
  MaskSettings mask;
  glm::vec3 background{0.0f};
  // What escaping rays see instead of the background; none: the background.
  std::shared_ptr<const Environment> environment;
  std::vector<Texture> textures;
  std::vector<Material> materials;
  std::vector<Light> lights;
  Geometry geometry;
  // What the loader let pass (a file an OBJ names that is missing), each once.
  std::vector<std::string> warnings;
};

}  // namespace glint
