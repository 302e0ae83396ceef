// What both ends of the wire queue for writing: one write in flight, the
// messages queued meanwhile gathered into the next, in order.
#include "proto/write_queue.h"

#include <gtest/gtest.h>

namespace glint::proto {
namespace {

std::vector<std::uint8_t> bytes(std::size_t n, std::uint8_t v) {
  return std::vector<std::uint8_t>(n, v);
}

TEST(WriteQueue, OneWriteInFlightGathersWhatWasQueuedInOrder) {
  WriteQueue q;
  q.push(bytes(3, 1));
  q.push(bytes(5, 2));
  EXPECT_EQ(q.queuedBytes(), 8u);
  const auto first = q.next(SIZE_MAX);
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0][0], 1);
  EXPECT_EQ(first[1].size(), 5u);
  EXPECT_TRUE(q.writing());
  q.push(bytes(7, 3));                    // queued behind the write in flight
  EXPECT_TRUE(q.next(SIZE_MAX).empty());  // one write at a time
  q.written();
  EXPECT_FALSE(q.writing());
  EXPECT_EQ(q.queuedBytes(), 7u);
  const auto second = q.next(SIZE_MAX);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(second[0][0], 3);
  q.written();
  EXPECT_TRUE(q.empty());
  EXPECT_TRUE(q.next(SIZE_MAX).empty());
  EXPECT_FALSE(q.writing());
}

TEST(WriteQueue, AGatherLimitCutsAWriteButTakesAtLeastOneMessage) {
  WriteQueue q;
  q.push(bytes(10, 1));
  q.push(bytes(10, 2));
  q.push(bytes(10, 3));
  EXPECT_EQ(q.next(15).size(), 2u);  // 10 < 15: a second message; 20 is not
  q.written();
  q.push(bytes(100, 4));
  EXPECT_EQ(q.next(1).size(), 1u);  // over the limit alone: still written
  q.written();
  EXPECT_EQ(q.next(1).size(), 1u);
}

}  // namespace
}  // namespace glint::proto
