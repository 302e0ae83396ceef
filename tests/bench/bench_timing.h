#pragma once

#include <functional>
#include <vector>

#include "common/base/timing.h"

namespace glint::bench {

// The median time of `runs` runs of `work`, in milliseconds.
inline double medianMs(int runs, const std::function<void()>& work) {
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    const Clock::time_point start = Clock::now();
    work();
    ms.push_back(msSince(start));
  }
  return median(std::move(ms));
}

}  // namespace glint::bench
