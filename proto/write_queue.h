#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

namespace glint::proto {

// Framed messages waiting to be written, whatever carries them (glintd's
// connections and glint's links alike), one write in flight at a time: a
// write gathers the messages queued meanwhile, in order, so that many small
// messages take one system call. Counts the bytes queued, for a carrier
// that bounds them.
class WriteQueue {
 public:
  void push(std::vector<std::uint8_t> frame);
  // The messages of the next write: those queued, from the first, while
  // fewer than `gatherBytes` are taken (at least one). Empty while a write
  // is in flight or nothing is queued; otherwise a write is in flight until
  // written().
  std::vector<std::span<const std::uint8_t>> next(std::size_t gatherBytes);
  // The write in flight finished: its messages leave the queue.
  void written();

  bool writing() const { return inFlight_ > 0; }
  bool empty() const { return frames_.empty(); }
  std::size_t queuedBytes() const { return queuedBytes_; }

 private:
  std::deque<std::vector<std::uint8_t>> frames_;
  std::size_t inFlight_ = 0;  // messages of frames_ in the write in flight
  std::size_t queuedBytes_ = 0;
};

}  // namespace glint::proto
