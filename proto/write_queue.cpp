#include "proto/write_queue.h"

namespace glint::proto {

void WriteQueue::push(std::vector<std::uint8_t> frame) {
  queuedBytes_ += frame.size();
  frames_.push_back(std::move(frame));
}

std::vector<std::span<const std::uint8_t>> WriteQueue::next(std::size_t gatherBytes) {
  std::vector<std::span<const std::uint8_t>> write;
  if (writing()) return write;
  std::size_t bytes = 0;
  for (; inFlight_ < frames_.size() && (inFlight_ == 0 || bytes < gatherBytes); ++inFlight_) {
    write.emplace_back(frames_[inFlight_]);
    bytes += frames_[inFlight_].size();
  }
  return write;
}

void WriteQueue::written() {
  for (; inFlight_ > 0; --inFlight_) {
    queuedBytes_ -= frames_.front().size();
    frames_.pop_front();
  }
}

}  // namespace glint::proto
