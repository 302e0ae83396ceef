#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <asio.hpp>
#include <asio/ssl.hpp>

namespace glint {

// The byte stream under a ServerLink: plain TCP, or TLS 1.3 over TCP. The
// link's protocol code is the same over either; only connecting (TLS adds
// the handshake and checks the server's certificate against the address
// dialled) and the words for a failure differ.
class LinkStream {
 public:
  using Done = std::function<void(const asio::error_code&, std::size_t)>;
  virtual ~LinkStream() = default;

  // Connects (and handshakes); `done` gets "" or what went wrong, in words.
  virtual void connect(const asio::ip::tcp::endpoint& endpoint, std::function<void(const std::string&)> done) = 0;
  // Writes all of `buffers` (TLS: joined first, one record run per write).
  virtual void write(const std::vector<asio::const_buffer>& buffers, Done done) = 0;
  virtual void readSome(asio::mutable_buffer buffer, Done done) = 0;
  // Words for a failed read or write: a TLS alert says the server refused
  // our certificate; a plain stream says the connection closed or broke.
  virtual std::string describe(const asio::error_code& error) = 0;
  virtual void close() = 0;
  virtual bool isOpen() const = 0;
};

std::unique_ptr<LinkStream> makePlainStream(asio::io_context& io);
// `host` is what was dialled (an IP address or a DNS name): the server's
// certificate must name it.
std::unique_ptr<LinkStream> makeTlsStream(asio::io_context& io, asio::ssl::context& tls, const std::string& host);

}  // namespace glint
