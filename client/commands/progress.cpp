#include "client/commands/progress.h"

#include <unistd.h>

#include <algorithm>

namespace glint {
namespace {

constexpr double kQuietSeconds = 1.0;          // kAuto: a frame shorter than this shows nothing
constexpr std::chrono::seconds kLineEvery{1};  // kForced, not a terminal: at most a line a second
// The time left is told once this many units (pixels, probes), and a
// hundredth of the total, have finished after the first ones seen: the pace
// is the rate of those, not the time from the start, which
// holds the set-up (the raster pass, the BVH, an upload) and the first
// tiles' latency, and once made a 0.7 s frame say "about 38 s left".
constexpr int kPaceUnits = 2;

}  // namespace

ProgressLine::ProgressLine(ProgressMode mode, std::FILE* out, bool terminal, std::string label, Clock::time_point start,
                           std::string unit)
    : mode_(mode), out_(out), terminal_(terminal), label_(std::move(label)), start_(start), unit_(std::move(unit)) {}

void ProgressLine::clear() {
  if (drawn_) std::fputs("\r\033[K", out_);
  drawn_ = false;
}

std::string ProgressLine::text(int done, int total, const Shares& shares, Clock::time_point now) const {
  char numbers[128];
  std::snprintf(numbers, sizeof numbers, ": %d/%d %s (%lld %%), %.1f s", done, total, unit_.c_str(),
                static_cast<long long>(done) * 100 / total, std::chrono::duration<double>(now - start_).count());
  std::string line = label_ + numbers;
  const int paced = done - paceDone_;
  if (paceDone_ > 0 && paced >= std::max(kPaceUnits, total / 100) && done < total) {
    const double perTile = std::chrono::duration<double>(now - paceStart_).count() / paced;
    std::snprintf(numbers, sizeof numbers, ", about %.0f s left", perTile * (total - done));
    line += numbers;
  }
  const std::string who = shares ? shares() : "";
  if (!who.empty()) line += "; " + who;
  return line;
}

void ProgressLine::update(int done, int total, const Shares& shares, Clock::time_point now) {
  if (mode_ == ProgressMode::kQuiet || total <= 0) return;
  if (paceDone_ == 0 && done > 0) {
    paceDone_ = done;
    paceStart_ = now;
  }
  if (terminal_) {
    if (mode_ == ProgressMode::kAuto && now - start_ < std::chrono::duration<double>(kQuietSeconds)) return;
    std::fprintf(out_, "\r\033[K%s", text(done, total, shares, now).c_str());
    drawn_ = true;
  } else {
    if (mode_ != ProgressMode::kForced) return;
    if (done < total && lastLine_ != Clock::time_point{} && now - lastLine_ < kLineEvery) return;
    std::fprintf(out_, "%s\n", text(done, total, shares, now).c_str());
    lastLine_ = now;
  }
  std::fflush(out_);
}

ProgressLine stderrProgress(ProgressMode mode, std::string label, std::string unit) {
  return ProgressLine(mode, stderr, isatty(STDERR_FILENO) == 1, std::move(label), ProgressLine::Clock::now(),
                      std::move(unit));
}

}  // namespace glint
