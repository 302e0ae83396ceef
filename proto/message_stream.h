#pragma once

#include <chrono>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include <asio.hpp>

#include "proto/framing.h"

namespace glint::proto {

// Why a stream operation failed.
class StreamError : public std::runtime_error {
 public:
  enum class Kind { kTimeout, kClosed, kBadMessage, kIo };
  StreamError(Kind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

// The client side of a framed connection, blocking with a timeout on every
// operation (the glint client and the tests; the server is asynchronous).
class MessageStream {
 public:
  // Connects; throws StreamError when it cannot within the timeout.
  MessageStream(const asio::ip::tcp::endpoint& endpoint, std::chrono::milliseconds timeout);

  void send(std::span<const std::uint8_t> bytes);
  // The next verified message. It stays valid until the next receive().
  const wire::Message& receive();
  void close();
  bool isOpen() const { return socket_.is_open(); }

  std::uint64_t bytesSent() const { return sent_; }
  std::uint64_t bytesReceived() const { return received_; }

 private:
  // Runs the I/O context until `done` or the timeout; false on timeout.
  bool runUntil(const bool& done);

  std::chrono::milliseconds timeout_;
  asio::io_context io_;
  asio::ip::tcp::socket socket_;
  std::vector<std::uint8_t> buffer_;  // received bytes
  std::size_t consumed_ = 0;          // of buffer_, already returned
  std::uint64_t sent_ = 0;
  std::uint64_t received_ = 0;
};

}  // namespace glint::proto
