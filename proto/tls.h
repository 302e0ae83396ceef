#pragma once

#include <string>

#include <asio/ssl.hpp>

namespace glint::proto {

// The files of one side of mutual TLS (PEM). glintd: its certificate and
// key, and the CA its clients' certificates must chain to; glint: the CA the
// server's certificate must chain to, and its own certificate and key.
struct TlsFiles {
  std::string ca;
  std::string cert;
  std::string key;
  bool any() const { return !ca.empty() || !cert.empty() || !key.empty(); }
};

// The option names a side uses for its files, for errors that name them.
struct TlsOptionNames {
  const char* ca;
  const char* cert;
  const char* key;
};
inline constexpr TlsOptionNames kServerTlsOptions{"--tls-client-ca", "--tls-cert", "--tls-key"};
inline constexpr TlsOptionNames kClientTlsOptions{"--tls-ca", "--tls-cert", "--tls-key"};

// TLS 1.3 contexts. The server's demands a client certificate chaining to
// files.ca; the client's verifies the server against files.ca and presents
// its own certificate where given. Throws InputError naming the option and
// file that is missing, unreadable or not what it should be (a key that does
// not match its certificate included).
asio::ssl::context serverTlsContext(const TlsFiles& files);
asio::ssl::context clientTlsContext(const TlsFiles& files);

// What a failed TLS operation means, in words a user can act on ("the
// server's certificate is not trusted by --tls-ca (self-signed certificate)",
// "the server refused our certificate (...)", "not speaking TLS").
// `verifyResult` is SSL_get_verify_result of the connection, when known.
std::string describeTlsFailure(const asio::error_code& error, long verifyResult, bool client);

}  // namespace glint::proto
