#include "proto/byte_stream.h"

#include <optional>

#include <openssl/ssl.h>
#include <openssl/x509v3.h>

#include "proto/tls.h"

namespace glint::proto {
namespace {

std::string connectFailure(const asio::error_code& error) {
  return "cannot connect (" + error.message() + "); is glintd running there?";
}

std::string streamFailure(const asio::error_code& error) {
  return error == asio::error::eof ? "closed the connection" : "connection lost (" + error.message() + ")";
}

void noDelay(asio::ip::tcp::socket& socket) {
  asio::error_code ignored;
  socket.set_option(asio::ip::tcp::no_delay(true), ignored);
}

void shutAndClose(asio::ip::tcp::socket& socket) {
  asio::error_code ignored;
  socket.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket.close(ignored);
}

class PlainStream : public ByteStream {
 public:
  PlainStream(asio::ip::tcp::socket socket, std::optional<asio::ip::tcp::endpoint> dial)
      : socket_(std::move(socket)), dial_(dial) {
    if (!dial_) noDelay(socket_);
  }
  void open(std::function<void(const std::string&)> done) override {
    if (!dial_) return done("");
    socket_.async_connect(*dial_, [this, done](const asio::error_code& e) {
      if (!e) noDelay(socket_);
      done(e ? connectFailure(e) : "");
    });
  }
  void write(const std::vector<asio::const_buffer>& buffers, Done done) override {
    asio::async_write(socket_, buffers, std::move(done));
  }
  void readSome(asio::mutable_buffer buffer, Done done) override { socket_.async_read_some(buffer, std::move(done)); }
  std::string describe(const asio::error_code& error) override { return streamFailure(error); }
  void close() override { shutAndClose(socket_); }
  bool isOpen() const override { return socket_.is_open(); }

 private:
  asio::ip::tcp::socket socket_;
  std::optional<asio::ip::tcp::endpoint> dial_;  // a client's: where to connect
};

class TlsStream : public ByteStream {
 public:
  TlsStream(asio::ip::tcp::socket socket, asio::ssl::context& tls, std::optional<asio::ip::tcp::endpoint> dial)
      : stream_(std::move(socket), tls), dial_(dial) {
    if (!dial_) noDelay(stream_.next_layer());
  }
  // OpenSSL checks the server's certificate against the address or name
  // dialled, so that a mismatch is reported as one (X509_V_ERR_IP_ADDRESS_MISMATCH ...).
  void expect(const std::string& host) {
    SSL* ssl = stream_.native_handle();
    asio::error_code notAnAddress;
    asio::ip::make_address(host, notAnAddress);
    if (notAnAddress) {
      SSL_set1_host(ssl, host.c_str());
      SSL_set_tlsext_host_name(ssl, host.c_str());  // SNI, for names only
    } else {
      X509_VERIFY_PARAM_set1_ip_asc(SSL_get0_param(ssl), host.c_str());
    }
  }
  void open(std::function<void(const std::string&)> done) override {
    if (!dial_) return handshake(asio::ssl::stream_base::server, done);
    stream_.next_layer().async_connect(*dial_, [this, done](const asio::error_code& e) {
      if (e) return done(connectFailure(e));
      noDelay(stream_.next_layer());
      handshake(asio::ssl::stream_base::client, done);
    });
  }
  void write(const std::vector<asio::const_buffer>& buffers, Done done) override {
    joined_.clear();
    for (const auto& b : buffers) {
      const auto* bytes = static_cast<const std::uint8_t*>(b.data());
      joined_.insert(joined_.end(), bytes, bytes + b.size());
    }
    asio::async_write(stream_, asio::buffer(joined_), std::move(done));
  }
  void readSome(asio::mutable_buffer buffer, Done done) override { stream_.async_read_some(buffer, std::move(done)); }
  // A TLS 1.3 server judges a client's certificate after the client's side
  // of the handshake is done: its refusal arrives as an alert on the
  // client's first read.
  std::string describe(const asio::error_code& error) override {
    const bool tls = error.category() == asio::error::get_ssl_category();
    if (!tls && (handshaken_ || error != asio::error::eof)) return streamFailure(error);
    return describeTlsFailure(error, SSL_get_verify_result(stream_.native_handle()), dial_.has_value());
  }
  void close() override { shutAndClose(stream_.next_layer()); }
  bool isOpen() const override { return stream_.next_layer().is_open(); }

 private:
  void handshake(asio::ssl::stream_base::handshake_type type, const std::function<void(const std::string&)>& done) {
    stream_.async_handshake(type, [this, done](const asio::error_code& h) {
      handshaken_ = !h;
      done(h ? describe(h) : "");
    });
  }

  asio::ssl::stream<asio::ip::tcp::socket> stream_;
  std::optional<asio::ip::tcp::endpoint> dial_;  // a client's: where to connect
  std::vector<std::uint8_t> joined_;             // the messages of the write in flight
  bool handshaken_ = false;
};

}  // namespace

std::unique_ptr<ByteStream> connectingStream(asio::io_context& io, const asio::ip::tcp::endpoint& endpoint) {
  return std::make_unique<PlainStream>(asio::ip::tcp::socket(io), endpoint);
}

std::unique_ptr<ByteStream> connectingTlsStream(asio::io_context& io, const asio::ip::tcp::endpoint& endpoint,
                                                asio::ssl::context& tls, const std::string& host) {
  auto stream = std::make_unique<TlsStream>(asio::ip::tcp::socket(io), tls, endpoint);
  stream->expect(host);
  return stream;
}

std::unique_ptr<ByteStream> acceptedStream(asio::ip::tcp::socket socket) {
  return std::make_unique<PlainStream>(std::move(socket), std::nullopt);
}

std::unique_ptr<ByteStream> acceptedTlsStream(asio::ip::tcp::socket socket, asio::ssl::context& tls) {
  return std::make_unique<TlsStream>(std::move(socket), tls, std::nullopt);
}

}  // namespace glint::proto
