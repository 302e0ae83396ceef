#include "common/scene/frame_limits.h"

#include <cmath>

#include "common/base/error.h"

namespace glint {
namespace {

std::string range(long long lo, long long hi) {
  return "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

}  // namespace

bool validSampleCount(SamplePattern pattern, int samples) {
  if (samples < 1) return false;
  if (pattern != SamplePattern::kRegular || samples == 2) return true;
  const int k = static_cast<int>(std::lround(std::sqrt(samples)));
  return k * k == samples;
}

std::optional<FrameProblem> frameProblem(const FrameSettings& f, std::size_t maxPixels) {
  using L = FrameLimits;
  if (f.width < 1 || f.height < 1 || f.width > L::kMaxEdge || f.height > L::kMaxEdge) {
    return FrameProblem{FrameField::kSize, std::to_string(f.width) + "x" + std::to_string(f.height) +
                                               ": width and height " + range(1, L::kMaxEdge)};
  }
  if (static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height) > maxPixels) {
    return FrameProblem{FrameField::kSize, "image of " + std::to_string(f.width) + "x" + std::to_string(f.height) +
                                               " pixels is over the limit of " + std::to_string(maxPixels)};
  }
  if (std::string camera = cameraProblem(f.camera); !camera.empty()) return FrameProblem{FrameField::kCamera, camera};
  if (f.sampling.samples < 1 || f.sampling.samples > L::kMaxSamples) {
    return FrameProblem{FrameField::kSamples, range(1, L::kMaxSamples)};
  }
  if (!validSampleCount(f.sampling.pattern, f.sampling.samples)) {
    return FrameProblem{FrameField::kSamples, "the regular pattern takes 1, 2 or a square number (4, 9, 16, ...) "
                                              "of samples; the other patterns take any number"};
  }
  if (f.sampling.seed > L::kMaxSeed) return FrameProblem{FrameField::kSeed, range(0, L::kMaxSeed)};
  if (f.tracing.maxDepth < 1 || f.tracing.maxDepth > L::kMaxDepth) {
    return FrameProblem{FrameField::kMaxDepth, range(1, L::kMaxDepth)};
  }
  if (f.tracing.maxBounces < 0 || f.tracing.maxBounces > L::kMaxBounces) {
    return FrameProblem{FrameField::kMaxBounces, range(0, L::kMaxBounces)};
  }
  if (!(f.tracing.minWeight >= 0.0f && f.tracing.minWeight <= 1.0f)) {
    return FrameProblem{FrameField::kMinWeight, "must be in [0, 1]"};
  }
  if (!(f.sampling.adaptiveThreshold > 0.0f && f.sampling.adaptiveThreshold <= 1.0f)) {
    return FrameProblem{FrameField::kAdaptiveThreshold, "must be in (0, 1]"};
  }
  if (!(f.sampling.perceptualThreshold > 0.0f && f.sampling.perceptualThreshold <= 1.0f)) {
    return FrameProblem{FrameField::kPerceptualThreshold, "must be in (0, 1]"};
  }
  if (f.sampling.lightSamples < 0 || f.sampling.lightSamples > L::kMaxLightSamples) {
    return FrameProblem{FrameField::kLightSamples, range(0, L::kMaxLightSamples) + " (0: each light's own)"};
  }
  if (!(std::abs(f.output.exposure) <= L::kMaxExposure)) {
    return FrameProblem{FrameField::kExposure, range(-static_cast<long long>(L::kMaxExposure), static_cast<long long>(L::kMaxExposure)) + " (EV)"};
  }
  return std::nullopt;
}

void checkFrame(const FrameSettings& frame, std::size_t maxPixels, const FrameFieldNames& names) {
  const std::optional<FrameProblem> p = frameProblem(frame, maxPixels);
  if (!p) return;
  switch (p->field) {
    case FrameField::kSize:
      throw InputError(std::string(names.size) + ": " + p->what);
    case FrameField::kCamera:
      throw InputError(std::string(names.camera) + p->what);
    case FrameField::kSamples:
      throw InputError(std::string(names.samples) + ": " + p->what);
    case FrameField::kSeed:
      throw InputError(std::string(names.seed) + ": " + p->what);
    case FrameField::kMaxDepth:
      throw InputError(std::string(names.maxDepth) + ": " + p->what);
    case FrameField::kMaxBounces:
      throw InputError(std::string(names.maxBounces) + ": " + p->what);
    case FrameField::kMinWeight:
      throw InputError(std::string(names.minWeight) + ": " + p->what);
    case FrameField::kAdaptiveThreshold:
      throw InputError(std::string(names.adaptiveThreshold) + ": " + p->what);
    case FrameField::kPerceptualThreshold:
      throw InputError(std::string(names.perceptualThreshold) + ": " + p->what);
    case FrameField::kLightSamples:
      throw InputError(std::string(names.lightSamples) + ": " + p->what);
    case FrameField::kExposure:
      throw InputError(std::string(names.exposure) + ": " + p->what);
  }
}

}  // namespace glint
