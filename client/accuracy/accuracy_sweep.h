#pragma once

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/base/enum_words.h"
#include "common/scene/scene.h"

namespace glint {

// The settings `glint accuracy` can vary.
enum class AccuracyKey {
  kSamples,
  kPattern,
  kFilter,
  kMaxDepth,
  kMinWeight,
  kMaskThreshold,
  kShadowMap,
  kMaskRule,
  kPerceptualThreshold,
  kLightSamples,
  kTransport,
  kMaxBounces,
  kFieldProbes,
  kFieldRays
};

template <>
struct EnumWords<AccuracyKey> {
  static constexpr std::array<std::pair<AccuracyKey, std::string_view>, 14> kWords{
      {{AccuracyKey::kSamples, "samples"},
       {AccuracyKey::kPattern, "pattern"},
       {AccuracyKey::kFilter, "filter"},
       {AccuracyKey::kMaxDepth, "max_depth"},
       {AccuracyKey::kMinWeight, "min_weight"},
       {AccuracyKey::kMaskThreshold, "mask_threshold"},
       {AccuracyKey::kShadowMap, "shadow_map"},
       {AccuracyKey::kMaskRule, "mask_rule"},
       {AccuracyKey::kPerceptualThreshold, "perceptual_threshold"},
       {AccuracyKey::kLightSamples, "light_samples"},
       {AccuracyKey::kTransport, "transport"},
       {AccuracyKey::kMaxBounces, "max_bounces"},
       {AccuracyKey::kFieldProbes, "field_probes"},
       {AccuracyKey::kFieldRays, "field_rays"}}};
};

// One series of a sweep: one key, the values it takes in turn, every other
// setting the scene's own.
struct Series {
  AccuracyKey key;
  std::vector<std::string> values;
};

// "--vary KEY=V1,V2,...": throws InputError naming the key and the values it
// takes when the key is unknown or a value is not one of them.
Series parseVary(const std::string& text);

// Every key, around the thesis's settings (what `--vary` not given sweeps);
// light_samples only for a scene with an area light, the field's keys only
// for one with an irradiance field.
std::vector<Series> defaultSweep(const Scene& scene);

// Whether a key's rows are hybrid frames (OpenGL draws, the tracer fills
// the mask): mask_threshold, shadow_map, mask_rule, perceptual_threshold and
// the irradiance field's field_probes and field_rays.
bool hybridKey(AccuracyKey key);

// Whether a key sets the irradiance field (path transport's, in the hybrid
// frame): field_probes and field_rays.
bool fieldKey(AccuracyKey key);

// Sets `value` of `key` in a frame and mask (mask_threshold: the material
// rule's reflectivity threshold and shadow_map the shadow maps' size, 0 none,
// under the scene's rule if it is auto or perceptual, else auto; mask_rule:
// the rule; perceptual_threshold: the sampling's, under the perceptual
// rule; field_probes and field_rays: the field's, the scene's own or the
// defaults for the other, under the scene's rule if it draws with OpenGL
// and traces by the materials, else auto). Values are as parseVary checked
// them.
void applySetting(AccuracyKey key, const std::string& value, FrameSettings& frame, MaskSettings& mask);

// The scene's own value of `key`, written as the sweep writes values (none,
// "", for perceptual_threshold under another rule than perceptual).
std::string currentValue(AccuracyKey key, const FrameSettings& frame, const MaskSettings& mask);

}  // namespace glint
