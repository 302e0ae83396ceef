#pragma once

#include <chrono>
#include <cstdio>

namespace glint {

// A progress bar on stderr for long renders: drawn only when stderr is a
// terminal and once the work has taken more than a second.
class ProgressBar {
 public:
  explicit ProgressBar(const char* label);
  ~ProgressBar();
  void update(int done, int total);

 private:
  const char* label_;
  bool terminal_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace glint
