#include "server/tile_scheduler.h"

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace glint::server {
namespace {

// With one worker, queued tasks of three clients run in turn, one each,
// whatever order and count they were submitted in.
TEST(TileScheduler, ClientsTakeTurns) {
  TileScheduler scheduler(1);
  std::mutex m;
  std::condition_variable cv;
  bool release = false;
  // Hold the only worker so everything below queues up first.
  scheduler.submit(99, [&] {
    std::unique_lock lock(m);
    cv.wait(lock, [&] { return release; });
  });
  std::vector<int> order;
  std::atomic<int> done{0};
  for (int i = 0; i < 6; ++i) scheduler.submit(1, [&] { std::lock_guard l(m); order.push_back(1); ++done; });
  for (int i = 0; i < 2; ++i) scheduler.submit(2, [&] { std::lock_guard l(m); order.push_back(2); ++done; });
  for (int i = 0; i < 2; ++i) scheduler.submit(3, [&] { std::lock_guard l(m); order.push_back(3); ++done; });
  {
    std::lock_guard lock(m);
    release = true;
  }
  cv.notify_all();
  while (done < 10) std::this_thread::yield();
  EXPECT_EQ(order, (std::vector<int>{1, 2, 3, 1, 2, 3, 1, 1, 1, 1}));
}

TEST(TileScheduler, CancelDropsQueuedWorkOfOneClient) {
  TileScheduler scheduler(1);
  std::mutex m;
  std::condition_variable cv;
  bool release = false;
  scheduler.submit(99, [&] {
    std::unique_lock lock(m);
    cv.wait(lock, [&] { return release; });
  });
  std::atomic<int> ran1{0}, ran2{0};
  for (int i = 0; i < 5; ++i) scheduler.submit(1, [&] { ++ran1; });
  for (int i = 0; i < 3; ++i) scheduler.submit(2, [&] { ++ran2; });
  EXPECT_EQ(scheduler.cancel(1), 5u);
  {
    std::lock_guard lock(m);
    release = true;
  }
  cv.notify_all();
  while (ran2 < 3) std::this_thread::yield();
  while (scheduler.queued() > 0) std::this_thread::yield();
  EXPECT_EQ(ran1, 0);
}

}  // namespace
}  // namespace glint::server
