#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <optional>

#include "common/base/thread_pool.h"

namespace glint::server {

// Runs work of many clients on a thread pool with a fair share: queued
// tasks are taken round robin, one per client in turn, so a client with a
// thousand queued tiles does not starve one with ten.
class TileScheduler {
 public:
  explicit TileScheduler(ThreadPool& pool) : pool_(pool) {}
  // Drops the queued tasks and waits for the running ones.
  ~TileScheduler();

  // A task's tag names it for cancel(client, which); untagged tasks (scene
  // builds) are dropped only with all of the client's.
  using Tag = std::optional<std::uint64_t>;

  int threads() const { return pool_.size(); }
  void submit(std::uint64_t client, std::function<void()> task, Tag tag = std::nullopt);
  // Drops the client's queued tasks (running ones finish). Returns how many.
  std::size_t cancel(std::uint64_t client);
  // Drops the client's queued tasks whose tag `which` accepts. Returns how many.
  std::size_t cancel(std::uint64_t client, const std::function<bool(std::uint64_t)>& which);
  std::size_t queued() const;

 private:
  void runOne();

  mutable std::mutex mutex_;
  struct Task {
    std::function<void()> run;
    Tag tag;
  };
  std::map<std::uint64_t, std::deque<Task>> queues_;
  std::deque<std::uint64_t> turn_;  // clients with queued work, in serving order
  std::size_t queued_ = 0;
  std::size_t inPool_ = 0;  // turns handed to the pool and not yet over
  std::condition_variable idle_;
  ThreadPool& pool_;
};

}  // namespace glint::server
