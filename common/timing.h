#pragma once

#include <chrono>

namespace glint {

using Clock = std::chrono::steady_clock;

// Milliseconds from `start` to now.
inline double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace glint
