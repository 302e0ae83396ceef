#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <asio.hpp>

#include "proto/byte_stream.h"
#include "proto/message_pipe.h"
#include "server/connection_registry.h"
#include "server/outbox.h"
#include "server/server.h"
#include "server/session.h"

namespace glint::server {

// One client: its message pipe (proto/message_pipe.h) hands verified
// messages to its Session; the connection sends the session's builds to
// SceneBuilds and its tiles to the scheduler (results come back through the
// Outbox), writes what comes back, and keeps the timeouts. Lives on the I/O
// thread; work on the pool reaches it only through asio::post. Nothing a
// client sends can stop the server or other clients: a connection that
// cannot go on is closed. The stream is plain TCP or TLS over it
// (proto/byte_stream.h), one design.
class Connection : public std::enable_shared_from_this<Connection>,
                   public ConnectionHandle,
                   private SessionHost,
                   public proto::PipeOwner {
 public:
  // `peer` names the client in the log ("10.0.0.2:51234").
  Connection(std::unique_ptr<proto::ByteStream> stream, ServerContext& context, std::uint64_t id, std::string peer);
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  void start();
  // Cancels queued work and closes the stream; safe to call twice.
  void close(const std::string& why) override;

 private:
  // SessionHost
  void reply(std::vector<std::uint8_t> frame) override;
  void end(const std::string& why) override;
  bool admit() override { return context_.registry.admit(id_); }
  void worked() override { context_.registry.worked(id_); }
  void build(SceneJob job) override;
  void trace(TileWork work) override;
  void cancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds) override;

  // proto::PipeOwner
  bool listening() const override { return !closed_ && !closeAfterWrites_; }
  std::size_t messageLimit() const override;
  void received(const wire::Message& message) override { session_.handle(message); }
  void refused(const proto::Decoded& bad) override;
  void readFailed(const asio::error_code& error) override;
  void afterRead(bool wasMid, bool took) override;
  void writeFailed(const asio::error_code& error) override { close(error.message()); }
  void drained() override;

  void waitForMessage();
  void armTimer(std::chrono::milliseconds timeout, const char* what);
  void onTimer(const char* what);
  void takeOutbox();  // on the I/O thread
  bool greeted() const { return session_.state() != Session::State::kAwaitingHello; }

  proto::MessagePipe pipe_;
  asio::steady_timer timer_;
  ServerContext& context_;
  std::uint64_t id_;
  Outbox outbox_;  // finished tiles from the pool
  Session session_;
  bool closeAfterWrites_ = false;
  bool closed_ = false;
  int pending_ = 0;  // tiles and scene builds queued or running for this client
};

}  // namespace glint::server
