#include "client/progress.h"

#include <unistd.h>

namespace glint {

ProgressBar::ProgressBar(const char* label)
    : label_(label), terminal_(isatty(STDERR_FILENO) == 1), start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fputs("\r\033[K", stderr);  // clear the bar line
}

void ProgressBar::update(int done, int total) {
  if (!terminal_ || total <= 0) return;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (seconds < 1.0) return;
  constexpr int kWidth = 40;
  const int filled = done * kWidth / total;
  char bar[kWidth + 1];
  for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
  bar[kWidth] = '\0';
  const double eta = done > 0 ? seconds * (total - done) / done : 0.0;
  std::fprintf(stderr, "\r%s [%s] %3d%%  %.1f s, about %.1f s left", label_, bar, done * 100 / total,
               seconds, eta);
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace glint
