// The client's blocking stream against a raw peer on loopback: a promise of
// bytes to come (SO_RCVLOWAT) never loses or delays a message.
#include "tests/support/message_stream.h"

#include <chrono>
#include <thread>
#include <vector>

#include <asio.hpp>
#include <gtest/gtest.h>

#include "proto/messages.h"
#include "tests/support/loopback_peer.h"

namespace glint::proto {
namespace {

using test::Peer;

using namespace std::chrono_literals;

std::vector<std::uint8_t> result(std::uint32_t tile, std::size_t pixelBytes) {
  return encodeTileResult(7, tile, std::vector<std::uint8_t>(pixelBytes, static_cast<std::uint8_t>(tile)), {}, 1);
}

// Three results of 40 000 pixel bytes, promised up front, written in 1000-byte
// pieces with pauses: every message comes through whole, in order, without
// waiting for a timeout.
TEST(MessageStream, PromisedBytesInSmallWritesAllArrive) {
  std::vector<std::uint8_t> bytes;
  for (std::uint32_t tile = 0; tile < 3; ++tile) {
    const auto r = result(tile, 40000);
    bytes.insert(bytes.end(), r.begin(), r.end());
  }
  Peer peer([&bytes](asio::ip::tcp::socket& socket) {
    for (std::size_t at = 0; at < bytes.size(); at += 1000) {
      asio::write(socket, asio::buffer(bytes.data() + at, std::min<std::size_t>(1000, bytes.size() - at)));
      if (at % 20000 == 0) std::this_thread::sleep_for(2ms);
    }
    std::this_thread::sleep_for(200ms);  // open while the client reads
  });
  MessageStream stream(peer.endpoint(), 5000ms);
  const auto start = std::chrono::steady_clock::now();
  std::size_t owed = 3 * 40000;
  for (std::uint32_t tile = 0; tile < 3; ++tile) {
    stream.expect(owed);
    const wire::TileResult* r = stream.receive().body_as_TileResult();
    ASSERT_NE(r, nullptr);
    EXPECT_EQ(r->tile_id(), tile);
    ASSERT_EQ(r->rgb()->size(), 40000u);
    EXPECT_EQ((*r->rgb())[39999], tile);
    owed -= 40000;
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, 2s);
  EXPECT_EQ(stream.bytesReceived(), bytes.size());
}

// A peer that sends less than was promised and closes: the reader gets what
// was sent, then "closed", at once rather than after its timeout.
TEST(MessageStream, ClosingWakesAReaderBelowItsWatermark) {
  const auto small = result(1, 300);
  Peer peer([&small](asio::ip::tcp::socket& socket) {
    std::this_thread::sleep_for(50ms);  // the client is waiting by now
    asio::write(socket, asio::buffer(small));
    std::this_thread::sleep_for(50ms);
    socket.close();
  });
  MessageStream stream(peer.endpoint(), 10000ms);
  const auto start = std::chrono::steady_clock::now();
  stream.expect(1 << 20);
  const wire::TileResult* r = stream.receive().body_as_TileResult();
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->tile_id(), 1u);
  try {
    stream.receive();
    ADD_FAILURE() << "a closed connection gave a message";
  } catch (const StreamError& e) {
    EXPECT_EQ(e.kind(), StreamError::Kind::kClosed);
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, 5s);
}

}  // namespace
}  // namespace glint::proto
