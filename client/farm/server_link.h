#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <asio.hpp>

#include "client/farm/server_conversation.h"
#include "proto/byte_stream.h"
#include "proto/message_pipe.h"

namespace glint {

class ServerLink;

// What a link tells its owner, always on the thread running the I/O context.
class LinkListener {
 public:
  virtual ~LinkListener() = default;
  virtual void linkReady(ServerLink& link) = 0;
  virtual void linkResult(ServerLink& link, std::uint32_t frameId, std::uint32_t tileId, TileOutput&& out) = 0;
  virtual void linkFailed(ServerLink& link, const LinkFailure& failure) = 0;
};

// One glintd seen from the client: its message pipe (proto/message_pipe.h)
// and the wait's timer. What is said, and what an answer means, is its
// ServerConversation's. Asynchronous on an io_context shared with the other
// links; owned through a shared_ptr so that handlers in flight outlive a
// link its owner dropped.
class ServerLink : public std::enable_shared_from_this<ServerLink>, private ConversationHost, public proto::PipeOwner {
 public:
  // `stream`, not yet open, is plain TCP or TLS (proto/byte_stream.h).
  ServerLink(asio::io_context& io, std::unique_ptr<proto::ByteStream> stream, std::size_t index, std::string name,
             const proto::SceneBundle& bundle, const proto::BundleDigest& digest, const LinkTimeouts& timeouts);
  ServerLink(const ServerLink&) = delete;
  ServerLink& operator=(const ServerLink&) = delete;

  void start(LinkListener& listener);
  // Stops telling the listener anything, and closes.
  void detach();

  void setupFrame(std::uint32_t frameId, const FrameSettings& frame, const proto::FrameWork& work = {}) {
    conversation_.setupFrame(frameId, frame, work);
  }
  void sendField(const IrradianceField& field) { conversation_.sendField(field); }
  void request(std::uint32_t frameId, std::uint32_t tileId, const TileJob& job) {
    conversation_.request(frameId, tileId, job);
  }
  void cancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds) { conversation_.cancel(frameId, tileIds); }
  // Fails the link from outside (the dispatcher found it stalled).
  void fail(LinkFailure::Kind kind, const std::string& what) { conversation_.fail(kind, what); }
  // Says Goodbye and closes once it is written.
  void close();

  std::size_t index() const { return index_; }
  const std::string& name() const { return name_; }
  bool ready() const { return conversation_.state() == ServerConversation::State::kReady; }
  bool failed() const { return conversation_.state() == ServerConversation::State::kFailed; }
  int threads() const { return conversation_.threads(); }
  bool uploaded() const { return conversation_.uploaded(); }
  std::uint64_t bytesSent() const { return pipe_.bytesSent(); }
  std::uint64_t bytesReceived() const { return pipe_.bytesReceived(); }

 private:
  // ConversationHost
  void send(std::vector<std::uint8_t> frame) override;
  void await(std::chrono::milliseconds timeout) override;
  void stopWaiting() override { timer_.cancel(); }
  void serving() override;
  void delivered(std::uint32_t frameId, std::uint32_t tileId, TileOutput&& out) override;
  void lost(const LinkFailure& failure) override;

  // proto::PipeOwner
  bool listening() const override { return !conversation_.over(); }
  std::size_t messageLimit() const override { return proto::kDefaultMaxMessageBytes; }
  void received(const wire::Message& message) override { conversation_.handle(message); }
  void refused(const proto::Decoded& bad) override;
  void readFailed(const asio::error_code& error) override;
  void wrote(std::size_t bytes) override { conversation_.wrote(bytes); }
  void writeFailed(const asio::error_code& error) override;
  void drained() override;
  bool closing() const { return conversation_.state() == ServerConversation::State::kClosed; }

  proto::MessagePipe pipe_;
  asio::steady_timer timer_;
  std::size_t index_;
  std::string name_;
  LinkListener* listener_ = nullptr;
  ServerConversation conversation_;
};

}  // namespace glint
