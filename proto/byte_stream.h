#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <asio.hpp>
#include <asio/ssl.hpp>

namespace glint::proto {

// The byte stream under either end of the wire: plain TCP, or TLS 1.3 over
// TCP. glint's links and glintd's connections speak through it the same way
// over either; only opening (TLS adds the handshake and checks the peer's
// certificate) and the words for a failure differ.
class ByteStream {
 public:
  using Done = std::function<void(const asio::error_code&, std::size_t)>;
  virtual ~ByteStream() = default;

  // Makes the stream ready: a client's connects (and over TLS handshakes);
  // an accepted one handshakes over TLS, and is ready at once over TCP.
  // `done` gets "" or what went wrong, in words.
  virtual void open(std::function<void(const std::string&)> done) = 0;
  // Writes all of `buffers` (TLS: joined first, one record run per write).
  virtual void write(const std::vector<asio::const_buffer>& buffers, Done done) = 0;
  virtual void readSome(asio::mutable_buffer buffer, Done done) = 0;
  // Words for a failed read or write: a TLS alert says the peer refused our
  // certificate; a plain stream says the connection closed or broke.
  virtual std::string describe(const asio::error_code& error) = 0;
  // Shuts the connection down and closes it.
  virtual void close() = 0;
  virtual bool isOpen() const = 0;
};

// A client's stream to `endpoint`. Over TLS, `host` is what was dialled (an
// IP address or a DNS name): the server's certificate must name it.
std::unique_ptr<ByteStream> connectingStream(asio::io_context& io, const asio::ip::tcp::endpoint& endpoint);
std::unique_ptr<ByteStream> connectingTlsStream(asio::io_context& io, const asio::ip::tcp::endpoint& endpoint,
                                                asio::ssl::context& tls, const std::string& host);
// A server's stream over an accepted socket.
std::unique_ptr<ByteStream> acceptedStream(asio::ip::tcp::socket socket);
std::unique_ptr<ByteStream> acceptedTlsStream(asio::ip::tcp::socket socket, asio::ssl::context& tls);

}  // namespace glint::proto
