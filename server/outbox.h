#pragma once

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

namespace glint::server {

// One connection's finished tiles on their way from the tracing pool to the
// I/O thread, which writes them. Results gather until the outbox holds
// kFlushBytes or none of the client's tiles is left waiting for a thread
// (fewer untraced than threads: the client's window has run dry, and it
// needs the results to send more before the threads idle); then one wake-up
// of the I/O thread takes them all into one gathered write. Each wake-up
// preempts a tracing thread where client and server share the cores; the
// writes saved and the flush size are measured in docs/protocol.md and
// docs/performance.md. Thread-safe.
class Outbox {
 public:
  static constexpr std::size_t kFlushBytes = 128 * 1024;

  explicit Outbox(int threads) : threads_(threads) {}
  Outbox(const Outbox&) = delete;
  Outbox& operator=(const Outbox&) = delete;

  // A tile went to the pool; its result will come through put().
  void expect();
  // A tile's result, from a pool thread. True when the caller is to wake the
  // I/O thread to take() (never twice before a take).
  bool put(std::vector<std::uint8_t> result);
  // `tiles` expected tiles were cancelled before they ran. True when what
  // the outbox holds is to be taken now: the cancelled were all it waited
  // for.
  bool forget(std::size_t tiles);
  // Everything held, in the order it came.
  std::vector<std::vector<std::uint8_t>> take();

 private:
  const int threads_;
  std::mutex mutex_;  // guards the four below
  std::vector<std::vector<std::uint8_t>> results_;
  std::size_t bytes_ = 0;
  int untraced_ = 0;         // expected, not yet put or forgotten
  bool wakePosted_ = false;  // a take() is on its way
};

}  // namespace glint::server
