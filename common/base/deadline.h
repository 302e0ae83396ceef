#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include "common/base/error.h"
#include "common/base/timing.h"

namespace glint {

// A limit on the time some `work` ("the scene's build") may take, checked
// where the work can stop (between its steps): past it, check() throws an
// InputError naming the place, the time taken and `limitName`, the setting
// a user changes. A limit of zero never passes.
class Deadline {
 public:
  Deadline(std::chrono::milliseconds limit, std::string work, std::string limitName)
      : start_(Clock::now()), limit_(limit), work_(std::move(work)), limitName_(std::move(limitName)) {}

  bool passed() const { return limit_.count() > 0 && Clock::now() - start_ > limit_; }

  void check(const std::string& place) const {
    if (!passed()) return;
    char text[96];
    std::snprintf(text, sizeof text, "has taken %.1f s, over %s of %.1f s", msSince(start_) / 1000.0,
                  limitName_.c_str(), static_cast<double>(limit_.count()) / 1000.0);
    throw InputError(place + ": " + work_ + " " + text);
  }

 private:
  Clock::time_point start_;
  std::chrono::milliseconds limit_;
  std::string work_;
  std::string limitName_;
};

}  // namespace glint
