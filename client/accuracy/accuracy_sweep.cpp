#include "client/accuracy/accuracy_sweep.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "common/base/error.h"
#include "common/scene/frame_limits.h"

namespace glint {
namespace {

// What a key takes, for errors and checks.
std::string allowed(AccuracyKey key) {
  switch (key) {
    case AccuracyKey::kSamples:
      return "whole numbers in [1, " + std::to_string(FrameLimits::kMaxSamples) + "]";
    case AccuracyKey::kPattern:
      return "one of " + enumWordsJoined<SamplePattern>();
    case AccuracyKey::kFilter:
      return "one of " + enumWordsJoined<FilterType>();
    case AccuracyKey::kMaxDepth:
      return "whole numbers in [1, " + std::to_string(FrameLimits::kMaxDepth) + "]";
    case AccuracyKey::kMinWeight:
    case AccuracyKey::kMaskThreshold:
      return "numbers in [0, 1]";
    case AccuracyKey::kShadowMap:
      return "whole numbers in [0, " + std::to_string(MaskSettings::kMaxShadowMap) + "]";
    case AccuracyKey::kMaskRule:
      return "one of " + enumWordsJoined<MaskRule>();
    case AccuracyKey::kPerceptualThreshold:
      return "numbers in (0, 1]";
    case AccuracyKey::kLightSamples:
      return "whole numbers in [1, " + std::to_string(FrameLimits::kMaxLightSamples) + "]";
    case AccuracyKey::kTransport:
      return "one of " + enumWordsJoined<Transport>();
    case AccuracyKey::kMaxBounces:
      return "whole numbers in [0, " + std::to_string(FrameLimits::kMaxBounces) + "]";
    case AccuracyKey::kFieldProbes:
      return "whole numbers in [" + std::to_string(FieldSettings::kMinProbes) + ", " +
             std::to_string(FieldSettings::kMaxProbes) + "]";
    case AccuracyKey::kFieldRays:
      return "powers of two from " + std::to_string(FieldSettings::kMinRays) + " to " +
             std::to_string(FieldSettings::kMaxRays);
  }
  return "";
}

// The rule a hybrid key's rows keep: the scene's if it draws with OpenGL
// and traces by the materials, else auto.
MaskRule hybridRule(MaskRule rule) { return rule == MaskRule::kPerceptual ? rule : MaskRule::kAuto; }

bool parseNumber(const std::string& text, double& out) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, out);
  return ec == std::errc() && ptr == end;
}

bool takes(AccuracyKey key, const std::string& value) {
  double number = 0.0;
  switch (key) {
    case AccuracyKey::kPattern:
      return enumFromWord<SamplePattern>(value).has_value();
    case AccuracyKey::kFilter:
      return enumFromWord<FilterType>(value).has_value();
    case AccuracyKey::kSamples:
      return parseNumber(value, number) && number == std::floor(number) && number >= 1 &&
             number <= FrameLimits::kMaxSamples;
    case AccuracyKey::kMaxDepth:
      return parseNumber(value, number) && number == std::floor(number) && number >= 1 &&
             number <= FrameLimits::kMaxDepth;
    case AccuracyKey::kMinWeight:
    case AccuracyKey::kMaskThreshold:
      return parseNumber(value, number) && number >= 0.0 && number <= 1.0;
    case AccuracyKey::kShadowMap:
      return parseNumber(value, number) && number == std::floor(number) && number >= 0 &&
             number <= MaskSettings::kMaxShadowMap;
    case AccuracyKey::kMaskRule:
      return enumFromWord<MaskRule>(value).has_value();
    case AccuracyKey::kPerceptualThreshold:
      return parseNumber(value, number) && number > 0.0 && number <= 1.0;
    case AccuracyKey::kLightSamples:
      return parseNumber(value, number) && number == std::floor(number) && number >= 1 &&
             number <= FrameLimits::kMaxLightSamples;
    case AccuracyKey::kTransport:
      return enumFromWord<Transport>(value).has_value();
    case AccuracyKey::kMaxBounces:
      return parseNumber(value, number) && number == std::floor(number) && number >= 0 &&
             number <= FrameLimits::kMaxBounces;
    case AccuracyKey::kFieldProbes:
      return parseNumber(value, number) && number == std::floor(number) && number >= FieldSettings::kMinProbes &&
             number <= FieldSettings::kMaxProbes;
    case AccuracyKey::kFieldRays:
      return parseNumber(value, number) && number == std::floor(number) && number >= FieldSettings::kMinRays &&
             number <= FieldSettings::kMaxRays && !FieldSettings::raysProblem(static_cast<int>(number));
  }
  return false;
}

// The frame's field, the scene's own or the defaults, to change.
FieldSettings& fieldOf(FrameSettings& frame) {
  if (!frame.tracing.field) frame.tracing.field.emplace();
  return *frame.tracing.field;
}

std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

Series parseVary(const std::string& text) {
  const auto equals = text.find('=');
  const std::string keyWord = text.substr(0, equals);
  const auto key = enumFromWord<AccuracyKey>(keyWord);
  if (equals == std::string::npos || !key) {
    throw UsageError("--vary " + text + ": expected KEY=V1,V2,... with KEY one of " + enumWordsJoined<AccuracyKey>());
  }
  Series series{*key, {}};
  std::stringstream list(text.substr(equals + 1));
  std::string value;
  while (std::getline(list, value, ',')) {
    if (!takes(*key, value)) {
      throw UsageError("--vary " + text + ": " + keyWord + " does not take '" + value + "'; it takes " + allowed(*key));
    }
    series.values.push_back(value);
  }
  if (series.values.empty()) throw UsageError("--vary " + text + ": no values; " + keyWord + " takes " + allowed(*key));
  return series;
}

std::vector<Series> defaultSweep(const Scene& scene) {
  if (scene.frame.tracing.transport == Transport::kPath) {
    // Every pixel is traced: the model (Whitted's missing light, bounces
    // cut short) beside the sampling.
    std::vector<Series> path{{AccuracyKey::kSamples, {"1", "4", "16", "64"}},
            {AccuracyKey::kPattern, {"jittered", "sobol"}},
            {AccuracyKey::kTransport, {"whitted", "path"}},
            {AccuracyKey::kMaxBounces, {"0", "1", "2", "4", "8"}},
            {AccuracyKey::kFilter, {"box", "tent", "gaussian", "mitchell"}}};
    if (scene.frame.tracing.field) {  // the field's bias against its time
      path.push_back({AccuracyKey::kFieldProbes, {"4", "8", "16"}});
      path.push_back({AccuracyKey::kFieldRays, {"64", "256", "1024"}});
    }
    return path;
  }
  std::vector<Series> sweep{{AccuracyKey::kSamples, {"1", "4", "16", "64"}},
          {AccuracyKey::kPattern, {"regular", "jittered", "adaptive", "perceptual"}},
          {AccuracyKey::kFilter, {"box", "tent", "gaussian", "mitchell"}},
          {AccuracyKey::kMaxDepth, {"1", "2", "3", "5", "8"}},
          {AccuracyKey::kMinWeight, {"0.1", "0.01", "0.001", "0"}},
          {AccuracyKey::kMaskThreshold, {"0", "0.1", "0.2", "0.5", "1"}},
          {AccuracyKey::kShadowMap, {"0", "256", "1024", "4096"}},
          {AccuracyKey::kMaskRule, {"auto", "perceptual"}},
          {AccuracyKey::kPerceptualThreshold, {"0.1", "0.2", "0.3", "0.5", "0.8"}}};
  const bool soft = std::any_of(scene.lights.begin(), scene.lights.end(), softLight);
  if (soft) sweep.push_back({AccuracyKey::kLightSamples, {"1", "4", "16", "64", "256"}});
  return sweep;
}

bool hybridKey(AccuracyKey key) {
  return key == AccuracyKey::kMaskThreshold || key == AccuracyKey::kShadowMap || key == AccuracyKey::kMaskRule ||
         key == AccuracyKey::kPerceptualThreshold || fieldKey(key);
}

bool fieldKey(AccuracyKey key) { return key == AccuracyKey::kFieldProbes || key == AccuracyKey::kFieldRays; }

void applySetting(AccuracyKey key, const std::string& value, FrameSettings& frame, MaskSettings& mask) {
  switch (key) {
    case AccuracyKey::kSamples:
      frame.sampling.samples = std::stoi(value);
      return;
    case AccuracyKey::kPattern:
      frame.sampling.pattern = *enumFromWord<SamplePattern>(value);
      return;
    case AccuracyKey::kFilter:
      frame.sampling.filter = *enumFromWord<FilterType>(value);
      return;
    case AccuracyKey::kMaxDepth:
      frame.tracing.maxDepth = std::stoi(value);
      return;
    case AccuracyKey::kMinWeight:
      frame.tracing.minWeight = std::stof(value);
      return;
    case AccuracyKey::kMaskThreshold:
      mask.rule = hybridRule(mask.rule);
      mask.minReflectivity = std::stof(value);
      return;
    case AccuracyKey::kShadowMap:
      mask.rule = hybridRule(mask.rule);
      mask.shadowMap = std::stoi(value);
      return;
    case AccuracyKey::kMaskRule:
      mask.rule = *enumFromWord<MaskRule>(value);
      return;
    case AccuracyKey::kPerceptualThreshold:
      mask.rule = MaskRule::kPerceptual;
      frame.sampling.perceptualThreshold = std::stof(value);
      return;
    case AccuracyKey::kLightSamples:
      frame.sampling.lightSamples = std::stoi(value);
      return;
    case AccuracyKey::kTransport:
      frame.tracing.transport = *enumFromWord<Transport>(value);
      return;
    case AccuracyKey::kMaxBounces:  // bounces are path transport's
      frame.tracing.transport = Transport::kPath;
      frame.tracing.maxBounces = std::stoi(value);
      return;
    case AccuracyKey::kFieldProbes:
      mask.rule = hybridRule(mask.rule);
      fieldOf(frame).probes = std::stoi(value);
      return;
    case AccuracyKey::kFieldRays:
      mask.rule = hybridRule(mask.rule);
      fieldOf(frame).rays = std::stoi(value);
      return;
  }
}

std::string currentValue(AccuracyKey key, const FrameSettings& frame, const MaskSettings& mask) {
  switch (key) {
    case AccuracyKey::kSamples:
      return std::to_string(frame.sampling.samples);
    case AccuracyKey::kPattern:
      return std::string(enumWord(frame.sampling.pattern));
    case AccuracyKey::kFilter:
      return std::string(enumWord(frame.sampling.filter));
    case AccuracyKey::kMaxDepth:
      return std::to_string(frame.tracing.maxDepth);
    case AccuracyKey::kMinWeight:
      return formatNumber(frame.tracing.minWeight);
    case AccuracyKey::kMaskThreshold:
      return formatNumber(mask.minReflectivity);
    case AccuracyKey::kShadowMap:
      return std::to_string(mask.shadowMap);
    case AccuracyKey::kMaskRule:
      return std::string(enumWord(mask.rule));
    case AccuracyKey::kPerceptualThreshold:  // the scene's own only where its rule uses it
      return mask.rule == MaskRule::kPerceptual ? formatNumber(frame.sampling.perceptualThreshold) : "";
    case AccuracyKey::kLightSamples:  // 0: each light's own
      return frame.sampling.lightSamples > 0 ? std::to_string(frame.sampling.lightSamples) : "";
    case AccuracyKey::kTransport:
      return std::string(enumWord(frame.tracing.transport));
    case AccuracyKey::kMaxBounces:
      return frame.tracing.transport == Transport::kPath ? std::to_string(frame.tracing.maxBounces) : "";
    case AccuracyKey::kFieldProbes:  // none: the scene has no field
      return frame.tracing.field ? std::to_string(frame.tracing.field->probes) : "";
    case AccuracyKey::kFieldRays:
      return frame.tracing.field ? std::to_string(frame.tracing.field->rays) : "";
  }
  return "";
}

}  // namespace glint
