#include "server/server.h"

#include "common/base/compute_pool.h"
#include "common/base/error.h"
#include "proto/byte_stream.h"
#include "proto/endpoint.h"
#include "server/connection.h"
#include "server/log.h"

namespace glint::server {

namespace {

// The memory options must fit one in another: a scene the cache cannot hold
// would be kept above --cache-mb, and the cache plus one scene being built
// must fit the whole.
const ServerOptions& checked(const ServerOptions& o) {
  const auto mb = [](std::size_t bytes) { return std::to_string(bytes >> 20); };
  if (o.maxSceneBytes > o.cacheBytes) {
    throw UsageError("--max-scene-mb " + mb(o.maxSceneBytes) + " is over --cache-mb " + mb(o.cacheBytes) +
                     ": the cache must be able to hold the largest scene");
  }
  if (o.cacheBytes + 2 * o.maxSceneBytes > o.maxMemoryBytes) {
    throw UsageError("--max-memory-mb " + mb(o.maxMemoryBytes) + " is below --cache-mb + 2 x --max-scene-mb (" +
                     mb(o.cacheBytes + 2 * o.maxSceneBytes) +
                     "): the scene cache, the uploaded files kept, and a "
                     "scene being built");
  }
  if (o.tls.any() && (o.tls.ca.empty() || o.tls.cert.empty() || o.tls.key.empty())) {
    throw UsageError(
        "TLS needs all three of --tls-cert, --tls-key and --tls-client-ca (deploy/glint-certs makes them)");
  }
  return o;
}

// Without TLS anyone who reaches the port may use glintd, read its clients'
// pixels and push their scenes out of the cache: only loopback, unless the
// user insists.
void checkExposure(const ServerOptions& o, const asio::ip::tcp::endpoint& endpoint) {
  if (o.tls.any() || endpoint.address().is_loopback()) return;
  if (!o.insecure) {
    throw UsageError("--listen " + o.listen +
                     ": not a loopback address, and without TLS anyone who reaches it can use glintd and read its "
                     "clients' pixels; give --tls-cert, --tls-key and --tls-client-ca (docs/deploy.md), or "
                     "--insecure if that is really meant");
  }
  logLine("warning: --insecure: listening on " + o.listen +
          " without TLS: anyone who reaches it can use glintd and read its clients' pixels");
}

}  // namespace

Server::Server(const ServerOptions& options)
    : options_(checked(options)),
      cache_(options.cacheBytes),
      files_(options.maxSceneBytes),
      ownPool_(options.computePool ? nullptr : std::make_unique<ThreadPool>(resolveThreadCount(options.threads))),
      scheduler_(ownPool_ ? *ownPool_ : computePool()),
      registry_(static_cast<std::size_t>(options.maxClients), static_cast<std::size_t>(options.maxWaiting)),
      buildMemory_(options.maxMemoryBytes - options.cacheBytes - options.maxSceneBytes,
                   "glintd --max-memory-mb less --cache-mb and the files kept (--max-scene-mb)"),
      builds_({options.maxSceneBytes, options.buildTimeout}, buildMemory_, SceneBuilds::threadsBeside(resolveThreadCount(options.threads))),
      context_{io_, scheduler_, cache_, files_, registry_, buildMemory_, builds_, options_},
      acceptor_(io_),
      acceptRetry_(io_),
      signals_(io_) {
  const asio::ip::tcp::endpoint endpoint = proto::parseEndpoint(options_.listen, "--listen");
  checkExposure(options_, endpoint);
  if (options_.tls.any()) tls_.emplace(proto::serverTlsContext(options_.tls));
  asio::error_code ec;
  acceptor_.open(endpoint.protocol(), ec);
  if (!ec) acceptor_.set_option(asio::ip::tcp::acceptor::reuse_address(true), ec);
  if (!ec) acceptor_.bind(endpoint, ec);
  if (!ec) acceptor_.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) throw InputError("--listen " + options_.listen + ": cannot listen (" + ec.message() + ")");
  port_ = acceptor_.local_endpoint().port();
  if (options_.handleSignals) {
    signals_.add(SIGINT);
    signals_.add(SIGTERM);
    signals_.async_wait([this](const asio::error_code& error, int signal) {
      if (error) return;  // cancelled: the server stopped another way
      logLine("signal " + std::to_string(signal) + ": shutting down");
      stop();
    });
  }
  accept();
}

Server::~Server() {
  io_.stop();
}

void Server::accept() {
  acceptor_.async_accept([this](const asio::error_code& error, asio::ip::tcp::socket socket) {
    if (error == asio::error::operation_aborted) return;  // stopping
    if (error) return acceptLater(error);
    const std::uint64_t id = nextId_++;
    std::string peer = proto::peerAddress(socket, "client " + std::to_string(id));
    auto stream = tls_ ? proto::acceptedTlsStream(std::move(socket), *tls_) : proto::acceptedStream(std::move(socket));
    admit(std::make_shared<Connection>(std::move(stream), context_, id, std::move(peer)), id);
    accept();
  });
}

// A new connection waits for its Hello (and first its TLS handshake) in the
// registry's waiting pool.
void Server::admit(std::shared_ptr<Connection> connection, std::uint64_t id) {
  registry_.addWaiting(id, connection);
  connection->start();
}

void Server::acceptLater(const asio::error_code& error) {
  logLine("accept failed: " + error.message());
  if (!acceptor_.is_open()) return;
  if (error == asio::error::no_descriptors) registry_.dropOldestWaiting("dropped: the server is out of descriptors");
  acceptRetry_.expires_after(std::chrono::milliseconds(50));
  acceptRetry_.async_wait([this](const asio::error_code& e) {
    if (!e) accept();
  });
}

void Server::run() {
  io_.run();
}

void Server::stop() {
  asio::post(io_, [this] {
    asio::error_code ignored;
    acceptor_.close(ignored);
    signals_.cancel(ignored);
    acceptRetry_.cancel();
    registry_.closeAll("server shutting down");
    io_.stop();
  });
}

}  // namespace glint::server
