// A connection's outbox: results gather while the client's tiles still wait
// for threads, and one wake-up takes them all once none waits, once they
// reach the flush size, or once a cancel leaves nothing else to wait for.
#include "server/outbox.h"

#include <gtest/gtest.h>

namespace glint::server {
namespace {

std::vector<std::uint8_t> result(std::size_t bytes) { return std::vector<std::uint8_t>(bytes, 1); }

TEST(Outbox, ResultsGatherUntilFewerTilesWaitThanThreads) {
  Outbox outbox(2);
  for (int i = 0; i < 5; ++i) outbox.expect();
  EXPECT_FALSE(outbox.put(result(10)));  // 4 still wait: the threads are busy
  EXPECT_FALSE(outbox.put(result(10)));  // 3
  EXPECT_FALSE(outbox.put(result(10)));  // 2
  EXPECT_TRUE(outbox.put(result(10)));   // 1 < 2 threads: wake the I/O thread
  EXPECT_FALSE(outbox.put(result(10)));  // a wake-up is on its way already
  EXPECT_EQ(outbox.take().size(), 5u);
  EXPECT_TRUE(outbox.take().empty());
}

TEST(Outbox, ALargeBatchIsFlushedWhileTilesStillWait) {
  Outbox outbox(1);
  for (int i = 0; i < 10; ++i) outbox.expect();
  EXPECT_FALSE(outbox.put(result(Outbox::kFlushBytes / 2)));
  EXPECT_TRUE(outbox.put(result(Outbox::kFlushBytes / 2)));
  EXPECT_EQ(outbox.take().size(), 2u);
  EXPECT_FALSE(outbox.put(result(10)));  // counted afresh after the take
}

TEST(Outbox, ACancelThatLeavesNothingToWaitForReleasesWhatIsHeld) {
  Outbox outbox(1);
  for (int i = 0; i < 4; ++i) outbox.expect();
  EXPECT_FALSE(outbox.put(result(10)));
  EXPECT_FALSE(outbox.forget(1));  // two still wait
  EXPECT_TRUE(outbox.forget(2));   // none: the held result goes now
  EXPECT_EQ(outbox.take().size(), 1u);
  EXPECT_FALSE(outbox.forget(0));  // nothing held
}

}  // namespace
}  // namespace glint::server
