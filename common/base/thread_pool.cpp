#include "common/base/thread_pool.h"

#include <algorithm>
#include <atomic>

namespace glint {

// A forked task's one run, claimed by whichever comes first: a worker, or
// the owner joining it.
struct ThreadPool::Forked::State {
  std::function<void()> task;
  std::atomic<bool> claimed{false};
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::exception_ptr error;

  bool claim() { return !claimed.exchange(true); }
  void run() {
    std::exception_ptr thrown;
    try {
      task();
    } catch (...) {
      thrown = std::current_exception();
    }
    task = nullptr;
    std::lock_guard lock(mutex);
    error = thrown;
    done = true;
    finished.notify_all();
  }
};

ThreadPool::Forked::~Forked() {
  if (!state_) return;
  try {
    join();
  } catch (...) {  // the owner left by an exception of its own; this one adds nothing
  }
}

void ThreadPool::Forked::join() {
  if (!state_) return;
  const std::shared_ptr<State> state = std::move(state_);
  if (state->claim()) state->run();
  std::unique_lock lock(state->mutex);
  state->finished.wait(lock, [&] { return state->done; });
  if (state->error) std::rethrow_exception(state->error);
}

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

ThreadPool::Forked ThreadPool::fork(std::function<void()> task) {
  auto state = std::make_shared<Forked::State>();
  state->task = std::move(task);
  submit([state] {
    if (state->claim()) state->run();
  });
  return Forked(std::move(state));
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
  const auto loop = [&] {
    try {
      for (std::size_t i = next++; i < count && !failed; i = next++) body(i);
    } catch (...) {
      failed = true;
      throw;
    }
  };
  // The caller is one of the runners; a helper no worker reached before
  // the indices ran out is run by join() and finds none left.
  const std::size_t helpers = std::min(count, static_cast<std::size_t>(size())) - 1;
  std::vector<Forked> forked;
  forked.reserve(helpers);
  for (std::size_t h = 0; h < helpers; ++h) forked.push_back(fork(loop));
  std::exception_ptr error;
  try {
    loop();
  } catch (...) {
    error = std::current_exception();
  }
  for (Forked& f : forked) {
    try {
      f.join();
    } catch (...) {
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
}

int resolveThreadCount(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace glint
