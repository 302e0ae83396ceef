#include "server/tile_scheduler.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace glint::server {
namespace {

// Occupies a scheduler's only worker until open() is called, so that
// everything submitted meanwhile queues up.
class Gate {
 public:
  explicit Gate(TileScheduler& scheduler) {
    scheduler.submit(99, [this] {
      std::unique_lock lock(mutex_);
      cv_.wait(lock, [this] { return open_; });
    });
  }
  void open() {
    {
      std::lock_guard lock(mutex_);
      open_ = true;
    }
    cv_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool open_ = false;
};

// With one worker, queued tasks of three clients run in turn, one each,
// whatever order and count they were submitted in.
TEST(TileScheduler, ClientsTakeTurns) {
  ThreadPool pool(1);
  TileScheduler scheduler(pool);
  Gate gate(scheduler);
  std::mutex m;
  std::vector<int> order;
  std::atomic<int> done{0};
  for (int i = 0; i < 6; ++i) scheduler.submit(1, [&] { std::lock_guard l(m); order.push_back(1); ++done; });
  for (int i = 0; i < 2; ++i) scheduler.submit(2, [&] { std::lock_guard l(m); order.push_back(2); ++done; });
  for (int i = 0; i < 2; ++i) scheduler.submit(3, [&] { std::lock_guard l(m); order.push_back(3); ++done; });
  gate.open();
  while (done < 10) std::this_thread::yield();
  EXPECT_EQ(order, (std::vector<int>{1, 2, 3, 1, 2, 3, 1, 1, 1, 1}));
}

TEST(TileScheduler, CancelDropsQueuedWorkOfOneClient) {
  ThreadPool pool(1);
  TileScheduler scheduler(pool);
  Gate gate(scheduler);
  std::atomic<int> ran1{0}, ran2{0};
  for (int i = 0; i < 5; ++i) scheduler.submit(1, [&] { ++ran1; });
  for (int i = 0; i < 3; ++i) scheduler.submit(2, [&] { ++ran2; });
  EXPECT_EQ(scheduler.cancel(1), 5u);
  gate.open();
  while (ran2 < 3) std::this_thread::yield();
  while (scheduler.queued() > 0) std::this_thread::yield();
  EXPECT_EQ(ran1, 0);
}

// Cancelling by tag drops only the tagged tasks it names; untagged tasks
// (scene builds) and other clients' tasks run.
TEST(TileScheduler, CancelByTagDropsOnlyTheNamedTasks) {
  ThreadPool pool(1);
  TileScheduler scheduler(pool);
  Gate gate(scheduler);
  std::mutex m;
  std::vector<int> ran;
  std::atomic<int> done{0};
  const auto record = [&](int id) {
    return [&, id] {
      std::lock_guard l(m);
      ran.push_back(id);
      ++done;
    };
  };
  for (int i = 0; i < 6; ++i) scheduler.submit(1, record(i), static_cast<std::uint64_t>(i));
  scheduler.submit(1, record(100));  // untagged
  scheduler.submit(2, record(200), 1);  // another client, same tag
  EXPECT_EQ(scheduler.cancel(1, [](std::uint64_t tag) { return tag % 2 == 1; }), 3u);
  gate.open();
  while (done < 5) std::this_thread::yield();
  EXPECT_EQ(scheduler.queued(), 0u);
  std::lock_guard l(m);
  std::sort(ran.begin(), ran.end());
  EXPECT_EQ(ran, (std::vector<int>{0, 2, 4, 100, 200}));
}

}  // namespace
}  // namespace glint::server
