#include "common/base/thread_pool.h"

#include <atomic>
#include <latch>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "common/base/compute_pool.h"

namespace glint {
namespace {

TEST(ThreadPool, ParallelForRunsEveryIndexOnce) {
  ThreadPool pool(3);
  std::vector<std::atomic<int>> runs(1000);
  pool.parallelFor(runs.size(), [&](std::size_t i) { ++runs[i]; });
  for (const std::atomic<int>& r : runs) EXPECT_EQ(r.load(), 1);
}

// A loop inside a loop on one worker: the worker's inner loop cannot wait
// for helpers queued behind itself, so the callers run the indices.
TEST(ThreadPool, NestedLoopsOnOneWorkerFinish) {
  ThreadPool pool(1);
  std::atomic<int> sum{0};
  pool.parallelFor(4, [&](std::size_t i) {
    pool.parallelFor(5, [&](std::size_t j) { sum += static_cast<int>(10 * i + j); });
  });
  EXPECT_EQ(sum.load(), 10 * (0 + 1 + 2 + 3) * 5 + 4 * (0 + 1 + 2 + 3 + 4));
}

TEST(ThreadPool, AForkNoWorkerTookRunsOnTheJoiner) {
  ThreadPool pool(1);
  std::latch release(1), busy(1);
  pool.submit([&] {
    busy.count_down();
    release.wait();
  });
  busy.wait();  // the one worker is held
  std::thread::id ranOn;
  ThreadPool::Forked forked = pool.fork([&] { ranOn = std::this_thread::get_id(); });
  forked.join();
  EXPECT_EQ(ranOn, std::this_thread::get_id());
  release.count_down();
}

TEST(ThreadPool, AForkAWorkerTookIsWaitedFor) {
  ThreadPool pool(1);
  std::atomic<bool> done{false};
  std::latch started(1);
  ThreadPool::Forked forked = pool.fork([&] {
    started.count_down();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    done = true;
  });
  started.wait();
  forked.join();
  EXPECT_TRUE(done.load());
}

TEST(ThreadPool, ErrorsReachTheJoinerAndStopTheLoop) {
  ThreadPool pool(2);
  ThreadPool::Forked forked = pool.fork([] { throw std::runtime_error("fork"); });
  EXPECT_THROW(forked.join(), std::runtime_error);
  std::atomic<int> ran{0};
  EXPECT_THROW(pool.parallelFor(100000,
                                [&](std::size_t i) {
                                  ++ran;
                                  if (i == 3) throw std::runtime_error("loop");
                                }),
               std::runtime_error);
  EXPECT_LT(ran.load(), 100000);
}

TEST(ComputePool, IsSizedOnceByThreads) {
  setComputeThreads(3);
  EXPECT_EQ(computePool().size(), 3);
  EXPECT_NO_THROW(setComputeThreads(3));
  EXPECT_THROW(setComputeThreads(2), std::logic_error);
}

}  // namespace
}  // namespace glint
