#include "proto/framing.h"

#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "proto/messages.h"
#include "tests/support/hostile_frames.h"

namespace glint::proto {
namespace {

std::span<const std::uint8_t> bytesOf(const std::vector<std::uint8_t>& v) { return {v.data(), v.size()}; }

// decodeFrame with aligned storage that lives as long as the test program
// (every message of these tests lies at +4 and is copied).
Decoded decodeFrame(std::span<const std::uint8_t> bytes, std::size_t maxMessageBytes) {
  static std::vector<std::uint64_t> aligned;
  return proto::decodeFrame(bytes, maxMessageBytes, aligned);
}

TEST(Framing, WholeFrameDecodesAndPartialNeedsMore) {
  const std::vector<std::uint8_t> frame = encodeHello(1000, 4, "test");
  const Decoded d = decodeFrame(bytesOf(frame), kDefaultMaxMessageBytes);
  ASSERT_EQ(d.status, DecodeStatus::kGood) << d.error;
  EXPECT_EQ(d.consumed, frame.size());
  EXPECT_EQ(d.message->body_type(), wire::Body::Hello);
  for (std::size_t n = 0; n < frame.size(); ++n) {
    EXPECT_EQ(decodeFrame(bytesOf(frame).first(n), kDefaultMaxMessageBytes).status, DecodeStatus::kNeedMore) << n;
  }
  // Two frames back to back: the first is decoded, the rest left.
  std::vector<std::uint8_t> two = frame;
  two.insert(two.end(), frame.begin(), frame.end());
  EXPECT_EQ(decodeFrame(bytesOf(two), kDefaultMaxMessageBytes).consumed, frame.size());
}

TEST(Framing, LengthOverTheLimitIsRejectedBeforeReadingTheBody) {
  const std::vector<std::uint8_t> header = {0xff, 0xff, 0xff, 0x7f};  // 2 GiB announced, no body
  const Decoded d = decodeFrame(bytesOf(header), 1 << 20);
  EXPECT_EQ(d.status, DecodeStatus::kBad);
  EXPECT_EQ(d.code, wire::ErrorCode::TooLarge);
  EXPECT_NE(d.error.find("over the limit"), std::string::npos);
}

TEST(Framing, NotGlintAtAll) {
  const std::string http = "GET / HTTP/1.1\r\nHost: localhost\r\n\r\n";
  const std::vector<std::uint8_t> bytes(http.begin(), http.end());
  EXPECT_EQ(decodeFrame(bytesOf(bytes), kDefaultMaxMessageBytes).status, DecodeStatus::kBad);
  // A small length followed by bytes without the GLNT identifier.
  std::vector<std::uint8_t> junk = {12, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  const Decoded d = decodeFrame(bytesOf(junk), kDefaultMaxMessageBytes);
  EXPECT_EQ(d.status, DecodeStatus::kBad);
  EXPECT_NE(d.error.find("GLNT"), std::string::npos);
}

// A union type without its table verifies as FlatBuffers; glintd used to
// dereference the missing body. The frame is rejected here, so no
// receiver ever sees it.
TEST(Framing, BodyTypeWithoutBodyIsRejected) {
  for (const wire::Body type : test::allBodyTypes()) {
    const std::vector<std::uint8_t> frame = test::bodylessFrame(type);
    const Decoded d = decodeFrame(bytesOf(frame), kDefaultMaxMessageBytes);
    EXPECT_EQ(d.status, DecodeStatus::kBad) << wire::EnumNameBody(type);
    EXPECT_NE(d.error.find("carries none"), std::string::npos) << d.error;
  }
}

// A message in the middle of a stream rarely lies 8-aligned; FlatBuffers
// reads its fields in place, so it is verified in an aligned copy (UBSan and
// the fuzzer found misaligned reads when it was verified where it lay).
TEST(Framing, MessagesAreVerifiedWhereTheyLieAligned) {
  const std::vector<std::uint8_t> frame = encodeTileResult(1, 2, std::vector<std::uint8_t>(9, 7), {1, 2, 3, 4, 5, 6}, 3);
  std::vector<std::uint64_t> storage(frame.size() / 8 + 2);
  for (std::size_t shift = 0; shift < 8; ++shift) {
    auto* at = reinterpret_cast<std::uint8_t*>(storage.data()) + shift;
    std::memcpy(at, frame.data(), frame.size());
    std::vector<std::uint64_t> aligned;
    const Decoded d = proto::decodeFrame({at, frame.size()}, kDefaultMaxMessageBytes, aligned);
    ASSERT_EQ(d.status, DecodeStatus::kGood) << shift << ": " << d.error;
    const wire::RayCounts* rays = d.message->body_as_TileResult()->rays();
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(rays) % alignof(std::uint64_t), 0u) << shift;
    EXPECT_EQ(rays->shadow_blocked(), 3u);
  }
  std::string error;
  const auto* off = reinterpret_cast<const std::uint8_t*>(storage.data()) + 4;
  EXPECT_EQ(verifyMessage({off, 16}, &error), nullptr);
  EXPECT_NE(error.find("not 8-aligned"), std::string::npos) << error;
}

// Every truncation of a message (with its length fixed up to match) and
// random corruptions are rejected or decoded safely, never crash.
TEST(Framing, TruncatedAndCorruptedMessagesAreRejected) {
  SceneBundle bundle{"{\"glint\": 1}", {{"a.obj", "v 0 0 0\n"}, {"b.png", std::string(100, 'x')}}};
  const std::vector<std::uint8_t> frame = encodeSceneUpload(bundle.hash(), bundle);
  const std::size_t body = frame.size() - kHeaderBytes;
  const SceneManifest whole = decodeManifest(*decodeFrame(bytesOf(frame), kDefaultMaxMessageBytes).message->body_as_SceneUpload());
  int rejected = 0;
  for (std::size_t n = 0; n < body; ++n) {
    std::vector<std::uint8_t> cut(frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(kHeaderBytes + n));
    cut[0] = static_cast<std::uint8_t>(n);
    cut[1] = static_cast<std::uint8_t>(n >> 8);
    cut[2] = cut[3] = 0;
    const Decoded d = decodeFrame(bytesOf(cut), kDefaultMaxMessageBytes);
    if (d.status == DecodeStatus::kBad) {
      ++rejected;
      continue;
    }
    // Only padding after the last object may go: what verifies is the whole message.
    const SceneManifest back = decodeManifest(*d.message->body_as_SceneUpload());
    EXPECT_EQ(back.text, whole.text) << n;
    EXPECT_EQ(back.files, whole.files) << n;
  }
  EXPECT_GE(rejected, static_cast<int>(body) - 7);
  std::mt19937 rng(5);
  for (int i = 0; i < 20'000; ++i) {
    std::vector<std::uint8_t> bad = frame;
    for (int k = 0; k < 3; ++k) bad[kHeaderBytes + rng() % body] = static_cast<std::uint8_t>(rng());
    const Decoded d = decodeFrame(bytesOf(bad), kDefaultMaxMessageBytes);
    if (d.status == DecodeStatus::kGood) {
      // Whatever still verifies must be safe to read.
      if (const auto* up = d.message->body_as_SceneUpload()) {
        try {
          (void)decodeManifest(*up);
        } catch (const std::exception&) {
        }
      }
    }
  }
}

}  // namespace
}  // namespace glint::proto
