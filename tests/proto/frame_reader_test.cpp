// The read policy both ends of the wire share: whole messages out of bytes
// that arrive in any pieces, memory that follows the bytes, not the header.
#include "proto/frame_reader.h"

#include <gtest/gtest.h>

#include <cstring>

#include "proto/messages.h"

namespace glint::proto {
namespace {

// Copies `bytes` into the reader as the stream would, in reads of at most `piece`.
void feed(FrameReader& reader, std::span<const std::uint8_t> bytes, std::size_t piece) {
  while (!bytes.empty()) {
    const std::span<std::uint8_t> space = reader.space();
    const std::size_t n = std::min({piece, space.size(), bytes.size()});
    std::memcpy(space.data(), bytes.data(), n);
    reader.filled(n);
    bytes = bytes.subspan(n);
  }
}

TEST(FrameReader, MessagesInOneReadOrByteByByteComeOutWholeAndInOrder) {
  const std::vector<std::uint8_t> hello = encodeHello(1 << 20, 2, "test");
  const std::vector<std::uint8_t> bye = encodeGoodbye();
  std::vector<std::uint8_t> both = hello;
  both.insert(both.end(), bye.begin(), bye.end());

  FrameReader together;
  feed(together, both, both.size());
  EXPECT_EQ(together.next(kDefaultMaxMessageBytes).message->body_type(), wire::Body::Hello);
  EXPECT_EQ(together.next(kDefaultMaxMessageBytes).message->body_type(), wire::Body::Goodbye);
  EXPECT_EQ(together.next(kDefaultMaxMessageBytes).status, DecodeStatus::kNeedMore);
  EXPECT_FALSE(together.midMessage());

  FrameReader apart;
  for (std::size_t i = 0; i + 1 < hello.size(); ++i) {
    feed(apart, std::span(hello).subspan(i, 1), 1);
    EXPECT_TRUE(apart.midMessage());
    ASSERT_EQ(apart.next(kDefaultMaxMessageBytes).status, DecodeStatus::kNeedMore) << i;
  }
  feed(apart, std::span(hello).last(1), 1);
  const Decoded d = apart.next(kDefaultMaxMessageBytes);
  ASSERT_EQ(d.status, DecodeStatus::kGood);
  EXPECT_EQ(d.message->body_as_Hello()->threads(), 2u);
  EXPECT_FALSE(apart.midMessage());
}

TEST(FrameReader, ALengthOverTheLimitIsRefusedOnItsHeaderAlone) {
  FrameReader reader;
  const std::uint8_t header[kHeaderBytes] = {0x00, 0x00, 0x00, 0x04};  // 64 MiB announced
  feed(reader, header, sizeof header);
  const Decoded d = reader.next(4096);
  EXPECT_EQ(d.status, DecodeStatus::kBad);
  EXPECT_EQ(d.code, wire::ErrorCode::TooLarge);
  EXPECT_NE(d.error.find("over the limit of 4096"), std::string::npos);
}

TEST(FrameReader, MemoryFollowsTheBytesThatArriveAndAnIdleReaderGivesItBack) {
  FrameReader reader;
  const std::uint8_t header[kHeaderBytes] = {0x00, 0x00, 0x00, 0x04};  // 64 MiB announced, 4 bytes sent
  feed(reader, header, sizeof header);
  EXPECT_EQ(reader.space().size(), kReadChunkBytes - kHeaderBytes);

  // A message of 1 MiB arriving in 64 KiB reads: the buffer at most doubles
  // what it holds, and once the message is taken a read gets the first size.
  const std::string big(std::size_t{1} << 20, 'x');
  const std::vector<std::uint8_t> chunk = encodeFileChunk({}, big.size(), 0, big);
  FrameReader large;
  std::size_t held = 0;
  for (std::size_t at = 0; at < chunk.size(); at += kReadChunkBytes) {
    const std::size_t n = std::min(kReadChunkBytes, chunk.size() - at);
    feed(large, std::span(chunk).subspan(at, n), n);
    held += n;
    EXPECT_LE(held + large.space().size(), 2 * std::max(held, kReadChunkBytes)) << held;
  }
  ASSERT_EQ(large.next(kDefaultMaxMessageBytes).status, DecodeStatus::kGood);
  EXPECT_EQ(large.space().size(), kReadChunkBytes);
}

TEST(FrameReader, TileKeysAreDistinctPerFrameAndTile) {
  EXPECT_NE(tileKey(1, 2), tileKey(2, 1));
  EXPECT_EQ(tileKey(3, 4) >> 32, 3u);
  EXPECT_EQ(static_cast<std::uint32_t>(tileKey(3, 4)), 4u);
}

}  // namespace
}  // namespace glint::proto
