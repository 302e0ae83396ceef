#pragma once

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>

namespace glint {

// How a long frame's progress shows on stderr: kAuto, redrawn in place on a
// terminal once the frame has taken a second, nothing otherwise; kForced
// (--progress), redrawn on a terminal from the start, and elsewhere (a log,
// a pipe) a line at most once a second; kQuiet (--quiet), never.
enum class ProgressMode { kAuto, kForced, kQuiet };

// One long step's progress line: units done of the total (a frame's pixels
// traced, an irradiance field's probes filled), the share each server
// traced, and, once the pace of the units is known, an estimate of the time
// left.
// Time is an input, so that what it prints can be tested.
class ProgressLine {
 public:
  using Clock = std::chrono::steady_clock;

  // `label` names the step ("rendering", "frame 3 of 30"), `unit` what it
  // counts ("pixels"); `terminal`: `out` is one, where a line is redrawn in
  // place.
  ProgressLine(ProgressMode mode, std::FILE* out, bool terminal, std::string label, Clock::time_point start,
               std::string unit = "pixels");
  // Clears a line drawn in place.
  ~ProgressLine() { clear(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // `shares` says who traced what, in words ("a 40 %, b 60 %"); asked only
  // when a line is printed, and may be empty.
  using Shares = std::function<std::string()>;
  void update(int done, int total, const Shares& shares, Clock::time_point now);
  // Clears a line drawn in place, once the step is over.
  void clear();

 private:
  std::string text(int done, int total, const Shares& shares, Clock::time_point now) const;

  ProgressMode mode_;
  std::FILE* out_;
  bool terminal_;
  std::string label_;
  Clock::time_point start_;
  std::string unit_;
  Clock::time_point lastLine_{};  // when the last line was printed (not on a terminal)
  bool drawn_ = false;            // a line is drawn in place
  int paceDone_ = 0;              // the units done when the first were seen, and when
  Clock::time_point paceStart_{};
};

// stderr, and whether it is a terminal.
ProgressLine stderrProgress(ProgressMode mode, std::string label, std::string unit = "pixels");

}  // namespace glint
