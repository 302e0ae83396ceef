#pragma once

#include <algorithm>
#include <cstdint>

namespace glint {

// Work counters of a render, by ray kind. Each thread or tile keeps its own
// and they are summed afterwards.
struct RayStats {
  std::uint64_t primary = 0;
  std::uint64_t shadow = 0;
  std::uint64_t shadowBlocked = 0;  // shadow rays that found an occluder
  std::uint64_t reflection = 0;
  std::uint64_t refraction = 0;
  std::uint64_t nonFiniteSamples = 0;  // samples discarded because a channel was NaN or infinite
  // Path transport's: the paths (one a camera sample, or one a sample the
  // irradiance field could not decide), their bounce rays (also counted in
  // reflection and refraction above, with Whitted's), the bounces of the
  // longest, and the lights' samples drawn for next-event estimation (a
  // shadow ray each, unless the light cannot reach the point).
  std::uint64_t paths = 0;
  std::uint64_t pathBounces = 0;
  std::uint64_t longestPath = 0;
  std::uint64_t lightSamples = 0;
  // Samples of the hybrid frame's tracer that the irradiance field could
  // not decide, traced as paths instead.
  std::uint64_t fieldUndecided = 0;

  RayStats& operator+=(const RayStats& o) {
    primary += o.primary;
    shadow += o.shadow;
    shadowBlocked += o.shadowBlocked;
    reflection += o.reflection;
    refraction += o.refraction;
    nonFiniteSamples += o.nonFiniteSamples;
    paths += o.paths;
    pathBounces += o.pathBounces;
    longestPath = std::max(longestPath, o.longestPath);
    lightSamples += o.lightSamples;
    fieldUndecided += o.fieldUndecided;
    return *this;
  }
  std::uint64_t total() const { return primary + shadow + reflection + refraction; }
};

}  // namespace glint
