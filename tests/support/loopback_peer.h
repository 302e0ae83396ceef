#pragma once

#include <cstdint>
#include <thread>
#include <vector>

#include <asio.hpp>

#include "proto/framing.h"

namespace glint::proto::test {

// A peer on loopback that accepts one connection and runs `script` on its
// socket, on a thread of its own: the other side of a client under test.
class Peer {
 public:
  template <typename Script>
  explicit Peer(Script script) : acceptor_(io_, asio::ip::tcp::endpoint(asio::ip::make_address("127.0.0.1"), 0)) {
    thread_ = std::thread([this, script] {
      asio::ip::tcp::socket socket(io_);
      acceptor_.accept(socket);
      script(socket);
    });
  }
  ~Peer() { thread_.join(); }
  Peer(const Peer&) = delete;
  Peer& operator=(const Peer&) = delete;
  asio::ip::tcp::endpoint endpoint() const { return acceptor_.local_endpoint(); }

 private:
  asio::io_context io_;
  asio::ip::tcp::acceptor acceptor_;
  std::thread thread_;
};

// Reads one whole frame's message bytes (no length prefix); empty when the
// connection closed first.
inline std::vector<std::uint8_t> readFrame(asio::ip::tcp::socket& socket) {
  std::uint8_t header[kHeaderBytes];
  asio::error_code error;
  asio::read(socket, asio::buffer(header), error);
  if (error) return {};
  std::vector<std::uint8_t> body(frameLength(std::span<const std::uint8_t, kHeaderBytes>(header, kHeaderBytes)));
  asio::read(socket, asio::buffer(body), error);
  return error ? std::vector<std::uint8_t>{} : body;
}

// Writes one frame whole; a client that closed already is not an error here.
inline void writeFrame(asio::ip::tcp::socket& socket, const std::vector<std::uint8_t>& frame) {
  asio::error_code ignored;
  asio::write(socket, asio::buffer(frame), ignored);
}

}  // namespace glint::proto::test
