#include "server/server.h"

#include "common/error.h"
#include "proto/endpoint.h"
#include "server/connection.h"
#include "server/log.h"

namespace glint::server {

Server::Server(const ServerOptions& options)
    : options_(options),
      cache_(options.cacheBytes),
      scheduler_(resolveThreadCount(options.threads)),
      context_{io_, scheduler_, cache_, options_},
      acceptor_(io_),
      signals_(io_) {
  const asio::ip::tcp::endpoint endpoint = proto::parseEndpoint(options_.listen, "--listen");
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

Server::~Server() { io_.stop(); }

void Server::accept() {
  acceptor_.async_accept([this](const asio::error_code& error, asio::ip::tcp::socket socket) {
    if (error) {
      if (error != asio::error::operation_aborted) logLine("accept failed: " + error.message());
      if (acceptor_.is_open()) accept();
      return;
    }
    std::erase_if(connections_, [](const auto& entry) { return entry.second.expired(); });
    const std::uint64_t id = nextId_++;
    auto connection = std::make_shared<Connection>(std::move(socket), context_, id);
    if (static_cast<int>(connections_.size()) >= options_.maxClients) {
      connection->refuse(wire::ErrorCode::Busy, "the server has its maximum of " +
                                                    std::to_string(options_.maxClients) + " clients; try later");
    } else {
      connections_[id] = connection;
      connection->start();
    }
    accept();
  });
}

void Server::run() { io_.run(); }

void Server::stop() {
  asio::post(io_, [this] {
    asio::error_code ignored;
    acceptor_.close(ignored);
    signals_.cancel(ignored);
    for (auto& [id, weak] : connections_) {
      if (const auto connection = weak.lock()) connection->close("server shutting down");
    }
    connections_.clear();
    io_.stop();
  });
}

}  // namespace glint::server
