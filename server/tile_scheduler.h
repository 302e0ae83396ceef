#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>

#include "common/thread_pool.h"

namespace glint::server {

// Runs work of many clients on one thread pool with a fair share: queued
// tasks are taken round robin, one per client in turn, so a client with a
// thousand queued tiles does not starve one with ten.
class TileScheduler {
 public:
  explicit TileScheduler(int threads);
  ~TileScheduler();

  int threads() const { return pool_.size(); }
  void submit(std::uint64_t client, std::function<void()> task);
  // Drops the client's queued tasks (running ones finish). Returns how many.
  std::size_t cancel(std::uint64_t client);
  std::size_t queued() const;

 private:
  void runOne();

  mutable std::mutex mutex_;
  std::map<std::uint64_t, std::deque<std::function<void()>>> queues_;
  std::deque<std::uint64_t> turn_;  // clients with queued work, in serving order
  std::size_t queued_ = 0;
  ThreadPool pool_;  // last member: its workers stop before the queues go away
};

}  // namespace glint::server
