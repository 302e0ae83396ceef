#include "common/base/thread_pool.h"

#include <algorithm>
#include <atomic>
#include <exception>

namespace glint {

ThreadPool::ThreadPool(int threads) {
  const int n = std::max(1, threads);
  workers_.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) workers_.emplace_back([this] { work(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  ready_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void ThreadPool::submit(std::function<void()> task) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(task));
  }
  ready_.notify_one();
}

void ThreadPool::work() {
  while (true) {
    std::function<void()> task;
    {
      std::unique_lock lock(mutex_);
      ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping and drained
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    task();
  }
}

void ThreadPool::parallelFor(std::size_t count, const std::function<void(std::size_t)>& body) {
  if (count == 0) return;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex doneMutex;
  std::condition_variable done;
  const std::size_t runners = std::min(count, static_cast<std::size_t>(size()));
  std::size_t running = runners;
  for (std::size_t r = 0; r < runners; ++r) {
    submit([&] {
      try {
        for (std::size_t i = next++; i < count && !failed; i = next++) body(i);
      } catch (...) {
        std::lock_guard lock(doneMutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
      std::lock_guard lock(doneMutex);
      if (--running == 0) done.notify_one();
    });
  }
  std::unique_lock lock(doneMutex);
  done.wait(lock, [&] { return running == 0; });
  if (error) std::rethrow_exception(error);
}

int resolveThreadCount(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace glint
