#pragma once

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

  RayStats& operator+=(const RayStats& o) {
    primary += o.primary;
    shadow += o.shadow;
    shadowBlocked += o.shadowBlocked;
    reflection += o.reflection;
    refraction += o.refraction;
    nonFiniteSamples += o.nonFiniteSamples;
    return *this;
  }
  std::uint64_t total() const { return primary + shadow + reflection + refraction; }
};

}  // namespace glint
