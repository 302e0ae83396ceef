#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "common/scene/scene.h"

namespace glint {

// The bounds of a frame's settings, defined once: the scene loader, the wire
// decoder and the command line all check a frame with frameProblem().
struct FrameLimits {
  static constexpr int kMaxEdge = 65536;                        // image width or height
  static constexpr std::size_t kMaxPixels = std::size_t{1} << 28;  // the rendered image
  static constexpr int kMaxSamples = 4096;                      // per pixel
  static constexpr int kMaxLightSamples = 4096;                 // shadow rays to a soft light per query
  static constexpr int kMaxDepth = 64;                          // primary ray = 1
  static constexpr int kMaxBounces = 256;                       // a path's bounces
  static constexpr std::uint32_t kMaxSeed = 0x7fffffff;
  static constexpr float kMaxExposure = 32.0f;                  // |EV|
};

// Which setting a problem is about, so that each caller names it its own way
// (the scene file's "sampling.samples", the wire's "frame_setup.samples", the
// command line's "--samples").
enum class FrameField {
  kSize,
  kCamera,
  kSamples,
  kMaxDepth,
  kMaxBounces,
  kMinWeight,
  kSeed,
  kAdaptiveThreshold,
  kPerceptualThreshold,
  kLightSamples,
  kExposure
};

struct FrameProblem {
  FrameField field;
  std::string what;  // "must be in [1, 64]"; for the camera, its field first: "eye: must be finite"
};

// Whether a pattern accepts this sample count (regular: a k x k grid, or 2;
// jittered, adaptive and perceptual: any count from 1).
bool validSampleCount(SamplePattern pattern, int samples);

// The first problem with a frame's settings, or none.
std::optional<FrameProblem> frameProblem(const FrameSettings& frame, std::size_t maxPixels = FrameLimits::kMaxPixels);

// How one caller names the settings in its errors.
struct FrameFieldNames {
  const char* size;
  const char* camera;  // a prefix: the camera problem names its own field ("eye: ...")
  const char* samples;
  const char* seed;
  const char* maxDepth;
  const char* maxBounces;
  const char* minWeight;
  const char* adaptiveThreshold;
  const char* perceptualThreshold;
  const char* lightSamples;
  const char* exposure;
};

// Throws InputError("<name>: <what>") for the first problem, if any.
void checkFrame(const FrameSettings& frame, std::size_t maxPixels, const FrameFieldNames& names);

}  // namespace glint
