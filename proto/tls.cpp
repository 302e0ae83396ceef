#include "proto/tls.h"

#include <cerrno>
#include <cstring>
#include <fstream>

#include <openssl/err.h>
#include <openssl/ssl.h>
#include <openssl/x509_vfy.h>

#include "common/base/error.h"

namespace glint::proto {
namespace {

// The file named by an option must exist and be readable before OpenSSL is
// asked to parse it, so that the error says which.
void checkReadable(const char* option, const std::string& path) {
  if (path.empty()) throw InputError(std::string(option) + ": no file given");
  std::ifstream in(path);
  if (!in) throw InputError(std::string(option) + " " + path + ": cannot read it (" + std::strerror(errno) + ")");
}

void check(const asio::error_code& error, const char* option, const std::string& path, const char* what) {
  if (error) throw InputError(std::string(option) + " " + path + ": " + what + " (" + error.message() + ")");
}

asio::ssl::context tls13(asio::ssl::context::method method) {
  asio::ssl::context context(method);
  SSL_CTX_set_min_proto_version(context.native_handle(), TLS1_3_VERSION);
  SSL_CTX_set_max_proto_version(context.native_handle(), TLS1_3_VERSION);
  return context;
}

void loadIdentity(asio::ssl::context& context, const TlsFiles& files, const TlsOptionNames& names) {
  checkReadable(names.cert, files.cert);
  checkReadable(names.key, files.key);
  asio::error_code error;
  context.use_certificate_chain_file(files.cert, error);
  check(error, names.cert, files.cert, "not a PEM certificate");
  context.use_private_key_file(files.key, asio::ssl::context::pem, error);
  check(error, names.key, files.key, (std::string("not a PEM private key, or not the key of ") + names.cert).c_str());
  if (SSL_CTX_check_private_key(context.native_handle()) != 1) {
    throw InputError(std::string(names.key) + " " + files.key + ": not the key of " + names.cert + " " + files.cert);
  }
}

void loadCa(asio::ssl::context& context, const TlsFiles& files, const TlsOptionNames& names) {
  checkReadable(names.ca, files.ca);
  asio::error_code error;
  context.load_verify_file(files.ca, error);
  check(error, names.ca, files.ca, "not a PEM CA certificate");
}

// Why the peer's certificate failed verification, in the words of the
// options that decide it.
std::string untrustedPeer(long verifyResult, bool client) {
  const std::string whose = client ? "the server's certificate" : "the client's certificate";
  switch (verifyResult) {
    case X509_V_ERR_CERT_HAS_EXPIRED:
      return whose + " has expired (make a new one with deploy/glint-certs)";
    case X509_V_ERR_CERT_NOT_YET_VALID:
      return whose + " is not valid yet (it starts in the future: are both hosts' clocks right?)";
    case X509_V_ERR_INVALID_PURPOSE:
      return whose + (client ? " is not a server's (extendedKeyUsage serverAuth; deploy/glint-certs DIR server ...)"
                             : " is not a client's (extendedKeyUsage clientAuth; deploy/glint-certs DIR client ...)");
    default:
      return whose +
             (client ? " is not trusted by --tls-ca or not for this address (" : " is not signed by --tls-client-ca (") +
             X509_verify_cert_error_string(verifyResult) + ")";
  }
}

}  // namespace

asio::ssl::context serverTlsContext(const TlsFiles& files) {
  asio::ssl::context context = tls13(asio::ssl::context::tls_server);
  loadIdentity(context, files, kServerTlsOptions);
  loadCa(context, files, kServerTlsOptions);
  context.set_verify_mode(asio::ssl::verify_peer | asio::ssl::verify_fail_if_no_peer_cert);
  return context;
}

asio::ssl::context clientTlsContext(const TlsFiles& files) {
  asio::ssl::context context = tls13(asio::ssl::context::tls_client);
  loadCa(context, files, kClientTlsOptions);
  if (!files.cert.empty() || !files.key.empty()) loadIdentity(context, files, kClientTlsOptions);
  context.set_verify_mode(asio::ssl::verify_peer);
  return context;
}

std::string describeTlsFailure(const asio::error_code& error, long verifyResult, bool client) {
  const std::string detail = error.message();
  if (error.category() != asio::error::get_ssl_category()) {
    if (error == asio::error::eof || error == asio::error::connection_reset) {
      return client ? "closed the connection during the TLS handshake (is it glintd without --tls-cert? then "
                      "drop --tls-ca; or it refused our certificate)"
                    : "the client closed the connection during the TLS handshake";
    }
    return "TLS failed (" + detail + ")";
  }
  const int reason = ERR_GET_REASON(static_cast<unsigned long>(error.value()));
  switch (reason) {
    case SSL_R_WRONG_VERSION_NUMBER:
    case SSL_R_PACKET_LENGTH_TOO_LONG:
    case SSL_R_HTTP_REQUEST:
    case SSL_R_UNSUPPORTED_PROTOCOL:
      return client ? "the server is not speaking TLS 1.3 (is it glintd without --tls-cert?) (" + detail + ")"
                    : "the client is not speaking TLS 1.3 (a glint without --tls-ca?) (" + detail + ")";
    case SSL_R_CERTIFICATE_VERIFY_FAILED:
      return untrustedPeer(verifyResult, client);
    case SSL_R_SSLV3_ALERT_CERTIFICATE_EXPIRED:
      return client ? "the server refused our certificate: it has expired (make a new one with deploy/glint-certs)"
                    : "the client refused our certificate: it has expired";
    case SSL_R_SSLV3_ALERT_UNSUPPORTED_CERTIFICATE:
      return client ? "the server refused our certificate: it is not a client's (extendedKeyUsage clientAuth; "
                      "deploy/glint-certs DIR client NAME)"
                    : "the client refused our certificate: it is not a server's (extendedKeyUsage serverAuth)";
    case SSL_R_PEER_DID_NOT_RETURN_A_CERTIFICATE:
      return "the client presented no certificate (glint needs --tls-cert and --tls-key)";
    case SSL_R_TLSV13_ALERT_CERTIFICATE_REQUIRED:
    case SSL_R_SSLV3_ALERT_BAD_CERTIFICATE:
    case SSL_R_TLSV1_ALERT_UNKNOWN_CA:
    case SSL_R_SSLV3_ALERT_CERTIFICATE_UNKNOWN:
    case SSL_R_TLSV1_ALERT_DECRYPT_ERROR:
      return client ? "the server refused our certificate (--tls-cert not signed by its --tls-client-ca, or none "
                      "given) (" + detail + ")"
                    : "the client refused our certificate (" + detail + ")";
    default:
      return "TLS failed (" + detail + ")";
  }
}

}  // namespace glint::proto
