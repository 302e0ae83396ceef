#include "proto/message_pipe.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <asio.hpp>
#include <gtest/gtest.h>

#include "proto/messages.h"

namespace glint::proto {
namespace {

// An end that keeps what its pipe tells it.
class Recorder : public PipeOwner, public std::enable_shared_from_this<Recorder> {
 public:
  explicit Recorder(std::unique_ptr<ByteStream> stream, std::size_t gather = SIZE_MAX)
      : pipe(std::move(stream), gather) {}
  void begin() {
    pipe.start(shared_from_this());
    pipe.stream().open([this](const std::string& failure) {
      opened = failure.empty();
      pipe.read();
    });
  }

  bool listening() const override { return !stop; }
  std::size_t messageLimit() const override { return limit; }
  void received(const wire::Message& m) override { got.push_back(m.body_as_SceneReady()->build_ms()); }
  void refused(const Decoded& bad) override { refusal = bad.error; }
  void readFailed(const asio::error_code& error) override { readError = error; }
  void wrote(std::size_t bytes) override { written += bytes; }
  void writeFailed(const asio::error_code& error) override { writeError = error; }
  void drained() override { ++drains; }

  MessagePipe pipe;
  bool opened = false, stop = false;
  std::size_t limit = kDefaultMaxMessageBytes, written = 0;
  int drains = 0;
  std::vector<float> got;
  std::string refusal;
  asio::error_code readError, writeError;
};

SceneHash hashOf(std::uint8_t b) {
  SceneHash h{};
  h.fill(b);
  return h;
}

struct Loopback {
  asio::io_context io;
  std::shared_ptr<Recorder> server, client;

  explicit Loopback(std::size_t clientGather = SIZE_MAX) {
    asio::ip::tcp::acceptor acceptor(io, asio::ip::tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0));
    client = std::make_shared<Recorder>(connectingStream(io, acceptor.local_endpoint()), clientGather);
    client->begin();
    asio::ip::tcp::socket socket(io);
    bool accepted = false;
    acceptor.async_accept(socket, [&](const asio::error_code& error) { accepted = !error; });
    runUntil([&] { return accepted && client->opened; });
    server = std::make_shared<Recorder>(acceptedStream(std::move(socket)));
    server->begin();
    runUntil([&] { return server->opened; });
  }
  template <typename Done>
  void runUntil(Done done) {
    for (int i = 0; i < 500 && !done(); ++i) {
      io.restart();
      io.run_for(std::chrono::milliseconds(10));
    }
  }
};

TEST(MessagePipe, MessagesArriveWholeInOrderAndTheBytesAreCountedBothWays) {
  Loopback link(4096);  // the client's writes gather about 4 KiB each
  ASSERT_TRUE(link.client->opened && link.server->opened);
  constexpr int kCount = 2000;
  for (int i = 0; i < kCount; ++i) link.client->pipe.send(encodeSceneReady(hashOf(1), static_cast<float>(i)));
  link.runUntil([&] { return link.server->got.size() == kCount && !link.client->pipe.writing(); });
  ASSERT_EQ(link.server->got.size(), static_cast<std::size_t>(kCount));
  for (int i = 0; i < kCount; ++i) EXPECT_EQ(link.server->got[static_cast<std::size_t>(i)], static_cast<float>(i));
  EXPECT_EQ(link.client->pipe.bytesSent(), link.server->pipe.bytesReceived());
  EXPECT_EQ(link.client->written, link.client->pipe.bytesSent());
  EXPECT_GT(link.client->drains, 0);
  EXPECT_FALSE(link.client->pipe.writing());
  EXPECT_EQ(link.client->pipe.queuedBytes(), 0u);
}

TEST(MessagePipe, AMessageOverTheOwnersLimitIsRefusedAndReadingStops) {
  Loopback link;
  link.server->limit = 16;
  link.client->pipe.send(encodeSceneReady(hashOf(2), 1.0f));
  link.runUntil([&] { return !link.server->refusal.empty(); });
  EXPECT_FALSE(link.server->refusal.empty());
  EXPECT_TRUE(link.server->got.empty());
}

TEST(MessagePipe, APeerThatClosesEndsTheRead) {
  Loopback link;
  link.client->pipe.stream().close();
  link.runUntil([&] { return static_cast<bool>(link.server->readError); });
  EXPECT_EQ(link.server->readError, asio::error::eof);
}

TEST(MessagePipe, AnOwnerThatStopsListeningIsToldNothingMore) {
  Loopback link;
  link.server->stop = true;
  link.client->pipe.send(encodeSceneReady(hashOf(3), 7.0f));
  link.runUntil([&] { return !link.client->pipe.writing() && link.client->drains > 0; });
  link.io.restart();
  link.io.run_for(std::chrono::milliseconds(50));
  EXPECT_TRUE(link.server->got.empty());
}

}  // namespace
}  // namespace glint::proto
