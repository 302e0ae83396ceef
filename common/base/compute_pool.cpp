#include "common/base/compute_pool.h"

#include <atomic>
#include <stdexcept>

namespace glint {
namespace {

std::atomic<int> requested{0};
std::atomic<ThreadPool*> made{nullptr};

}  // namespace

void setComputeThreads(int threads) {
  const ThreadPool* pool = made.load();
  if (pool && pool->size() != resolveThreadCount(threads)) {
    throw std::logic_error("the compute pool already runs with another thread count");
  }
  requested = threads;
}

ThreadPool& computePool() {
  static ThreadPool pool(resolveThreadCount(requested));
  made = &pool;
  return pool;
}

}  // namespace glint
