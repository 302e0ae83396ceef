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

// A test's side of a framed connection, blocking with a timeout on every
// operation (tests that play a raw client; glint and glintd are asynchronous).
class MessageStream {
 public:
  // Connects; throws StreamError when it cannot within the timeout.
  MessageStream(const asio::ip::tcp::endpoint& endpoint, std::chrono::milliseconds timeout);

  void send(std::span<const std::uint8_t> bytes);
  // The next verified message. It stays valid until the next receive().
  const wire::Message& receive();
  // A promise that the peer will send at least `bytes` more without waiting
  // for anything from this side (0: no promise). receive() then sleeps until
  // min(bytes not yet read, 64 KiB) have arrived (SO_RCVLOWAT) instead of
  // waking for every small write; the connection closing wakes it too.
  void expect(std::size_t bytes) { expected_ = bytes; }
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
  std::vector<std::uint64_t> aligned_;  // an 8-aligned copy of the last message, where needed
  std::uint64_t sent_ = 0;
  std::uint64_t received_ = 0;
  std::size_t expected_ = 0;   // see expect()
  int lowWatermark_ = 1;       // SO_RCVLOWAT as last set
};

}  // namespace glint::proto
