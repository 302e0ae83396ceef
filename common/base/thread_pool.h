#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace glint {

// A fixed set of worker threads taking tasks from one queue.
class ThreadPool {
 public:
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()); }
  void submit(std::function<void()> task);

  // Runs body(i) for every i in [0, count) on the workers and waits. The
  // first exception a body throws is rethrown here, after every started body
  // has finished; the remaining indices are skipped.
  void parallelFor(std::size_t count, const std::function<void(std::size_t)>& body);

 private:
  void work();

  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<std::function<void()>> queue_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

// Worker count for a --threads value: 0 means every hardware thread.
int resolveThreadCount(int requested);

}  // namespace glint
