#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace glint {

// A fixed set of worker threads taking tasks from one queue. Work may be
// forked and joined, and loops run in parallel, from any thread, a worker
// included: a joining thread that finds its task not yet started runs it
// itself, so nested work never waits on a worker that is waiting too.
class ThreadPool {
 public:
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()); }
  void submit(std::function<void()> task);

  // A task handed to the workers that its owner joins: join() runs it on
  // the calling thread if no worker has taken it yet, else waits for it,
  // and rethrows what it threw. Joined on destruction (its error dropped).
  class Forked {
   public:
    Forked(Forked&&) = default;
    Forked& operator=(Forked&&) = delete;
    ~Forked();
    void join();

   private:
    friend class ThreadPool;
    struct State;
    explicit Forked(std::shared_ptr<State> state) : state_(std::move(state)) {}
    std::shared_ptr<State> state_;
  };
  [[nodiscard]] Forked fork(std::function<void()> task);

  // Runs body(i) for every i in [0, count) on the workers and the calling
  // thread, and waits. The first exception a body throws is rethrown here,
  // after every started body has finished; the remaining indices are skipped.
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
