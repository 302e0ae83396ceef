#pragma once

#include <cstddef>

#include <nlohmann/json.hpp>

#include "common/effects.h"
#include "common/ray_stats.h"

namespace glint {

// Timings of one frame, in milliseconds.
struct FrameTimes {
  double loadMs = 0.0;
  double bvhMs = 0.0;
  double traceMs = 0.0;
  double totalMs = 0.0;
};

// The --stats record of one frame (one JSON object per line).
nlohmann::json frameStats(int frame, int width, int height, std::size_t maskedPixels,
                          const RayStats& rays, const FrameTimes& times, const EffectPlan& plan,
                          std::size_t droppedTriangles);

}  // namespace glint
