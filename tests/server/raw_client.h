#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "tests/support/message_stream.h"
#include "proto/messages.h"

namespace glint::server::test {

// A raw connection for sending bytes that a real client never would.
class RawClient {
 public:
  // `wait`: how long a read waits for the server.
  explicit RawClient(std::uint16_t port, std::chrono::seconds wait = std::chrono::seconds(3))
      : stream_({asio::ip::make_address("127.0.0.1"), port}, wait) {}
  void write(const std::vector<std::uint8_t>& bytes) {
    try {
      stream_.send(bytes);
    } catch (const proto::StreamError&) {
      // The server may already have closed: what it said is read next.
    }
  }
  void write(const std::string& text) { write(std::vector<std::uint8_t>(text.begin(), text.end())); }
  // The next message, or nullptr once the server closed the connection or
  // the wait passed.
  const wire::Message* read() {
    try {
      return &stream_.receive();
    } catch (const proto::StreamError&) {
      return nullptr;
    }
  }
  // The next message must be an Error; returns its code and text.
  std::pair<wire::ErrorCode, std::string> readError() {
    const wire::Message* m = read();
    const auto* e = m ? m->body_as_Error() : nullptr;
    if (!e) return {wire::ErrorCode::Internal, m ? "(not an error)" : "(no message)"};
    return {e->code(), e->message() ? e->message()->str() : ""};
  }
  // True when the server closes the connection within the wait.
  bool closed() {
    try {
      while (true) stream_.receive();
    } catch (const proto::StreamError& e) {
      return e.kind() == proto::StreamError::Kind::kClosed;
    }
  }
  // Says Hello; true when the server answers with its own.
  bool hello() {
    write(proto::encodeHello(1 << 20, 0, "raw"));
    const wire::Message* m = read();
    return m && m->body_as_Hello();
  }

 private:
  proto::MessageStream stream_;
};

}  // namespace glint::server::test
