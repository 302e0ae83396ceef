#include "client/link_stream.h"

#include <openssl/ssl.h>
#include <openssl/x509v3.h>

#include "proto/tls.h"

namespace glint {
namespace {

std::string connectFailure(const asio::error_code& error) {
  return "cannot connect (" + error.message() + "); is glintd running there?";
}

std::string streamFailure(const asio::error_code& error) {
  return error == asio::error::eof ? "closed the connection" : "connection lost (" + error.message() + ")";
}

class PlainStream : public LinkStream {
 public:
  explicit PlainStream(asio::io_context& io) : socket_(io) {}
  void connect(const asio::ip::tcp::endpoint& endpoint, std::function<void(const std::string&)> done) override {
    socket_.async_connect(endpoint, [this, done](const asio::error_code& e) {
      if (!e) {
        asio::error_code ignored;
        socket_.set_option(asio::ip::tcp::no_delay(true), ignored);
      }
      done(e ? connectFailure(e) : "");
    });
  }
  void write(const std::vector<asio::const_buffer>& buffers, Done done) override {
    asio::async_write(socket_, buffers, std::move(done));
  }
  void readSome(asio::mutable_buffer buffer, Done done) override { socket_.async_read_some(buffer, std::move(done)); }
  std::string describe(const asio::error_code& error) override { return streamFailure(error); }
  void close() override {
    asio::error_code ignored;
    socket_.close(ignored);
  }
  bool isOpen() const override { return socket_.is_open(); }

 private:
  asio::ip::tcp::socket socket_;
};

class TlsStream : public LinkStream {
 public:
  // OpenSSL checks the certificate against the address or name dialled, so
  // that a mismatch is reported as one (X509_V_ERR_IP_ADDRESS_MISMATCH ...).
  TlsStream(asio::io_context& io, asio::ssl::context& tls, const std::string& host) : stream_(io, tls) {
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
  void connect(const asio::ip::tcp::endpoint& endpoint, std::function<void(const std::string&)> done) override {
    stream_.lowest_layer().async_connect(endpoint, [this, done](const asio::error_code& e) {
      if (e) {
        done(connectFailure(e));
        return;
      }
      asio::error_code ignored;
      stream_.lowest_layer().set_option(asio::ip::tcp::no_delay(true), ignored);
      stream_.async_handshake(asio::ssl::stream_base::client, [this, done](const asio::error_code& h) {
        handshaken_ = !h;
        done(h ? describe(h) : "");
      });
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
  // A TLS 1.3 server judges our certificate after our side of the handshake
  // is done: its refusal arrives as an alert on the first read.
  std::string describe(const asio::error_code& error) override {
    const bool tls = error.category() == asio::error::get_ssl_category();
    if (!tls && (handshaken_ || error != asio::error::eof)) return streamFailure(error);
    return proto::describeTlsFailure(error, SSL_get_verify_result(stream_.native_handle()), true);
  }
  void close() override {
    asio::error_code ignored;
    stream_.lowest_layer().close(ignored);
  }
  bool isOpen() const override { return stream_.lowest_layer().is_open(); }

 private:
  asio::ssl::stream<asio::ip::tcp::socket> stream_;
  std::vector<std::uint8_t> joined_;  // the messages of the write in flight
  bool handshaken_ = false;
};

}  // namespace

std::unique_ptr<LinkStream> makePlainStream(asio::io_context& io) { return std::make_unique<PlainStream>(io); }

std::unique_ptr<LinkStream> makeTlsStream(asio::io_context& io, asio::ssl::context& tls, const std::string& host) {
  return std::make_unique<TlsStream>(io, tls, host);
}

}  // namespace glint
