#include "server/outbox.h"

namespace glint::server {

void Outbox::expect() {
  std::lock_guard lock(mutex_);
  ++untraced_;
}

bool Outbox::put(std::vector<std::uint8_t> result) {
  std::lock_guard lock(mutex_);
  bytes_ += result.size();
  results_.push_back(std::move(result));
  --untraced_;
  const bool wake = !wakePosted_ && (untraced_ < threads_ || bytes_ >= kFlushBytes);
  wakePosted_ = wakePosted_ || wake;
  return wake;
}

bool Outbox::forget(std::size_t tiles) {
  std::lock_guard lock(mutex_);
  untraced_ -= static_cast<int>(tiles);
  return !wakePosted_ && untraced_ < threads_ && !results_.empty();
}

std::vector<std::vector<std::uint8_t>> Outbox::take() {
  std::lock_guard lock(mutex_);
  std::vector<std::vector<std::uint8_t>> results;
  results.swap(results_);
  bytes_ = 0;
  wakePosted_ = false;
  return results;
}

}  // namespace glint::server
