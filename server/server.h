#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include <asio.hpp>

#include "common/base/memory_gauge.h"
#include "server/connection_registry.h"
#include "server/scene_builds.h"
#include "server/scene_cache.h"
#include "server/server_options.h"
#include "server/tile_scheduler.h"

namespace glint::server {

class Connection;

// State the connections share; lives as long as the server.
struct ServerContext {
  asio::io_context& io;
  TileScheduler& scheduler;
  SceneCache& cache;
  FileStore& files;
  ConnectionRegistry& registry;
  // Scenes being built and files still arriving: --max-memory-mb less
  // --cache-mb and the file store (--max-scene-mb).
  MemoryGauge& buildMemory;
  SceneBuilds& builds;
  const ServerOptions& options;
};

// glintd: accepts clients, holds the scene cache and the tile scheduler.
// All socket I/O runs on the thread that calls run(); tracing runs on the
// scheduler's pool (the compute pool in glintd), scene builds on a pool of
// their own (SceneBuilds).
class Server {
 public:
  // Checks the options and binds the listening socket; throws InputError
  // when it cannot.
  explicit Server(const ServerOptions& options);
  ~Server();

  std::uint16_t port() const { return port_; }
  int threads() const { return scheduler_.threads(); }
  const SceneCache& cache() const { return cache_; }
  // Serves until stop(), SIGINT or SIGTERM.
  void run();
  // Stops accepting, cancels queued tiles and closes every connection; safe
  // from any thread.
  void stop();

 private:
  void accept();
  void admit(std::shared_ptr<Connection> connection, std::uint64_t id);
  // Accepting failed for want of resources (EMFILE): make room, try again soon.
  void acceptLater(const asio::error_code& error);

  ServerOptions options_;
  asio::io_context io_;
  SceneCache cache_;
  FileStore files_;
  std::unique_ptr<ThreadPool> ownPool_;  // where the options do not name the compute pool
  TileScheduler scheduler_;
  ConnectionRegistry registry_;
  MemoryGauge buildMemory_;
  SceneBuilds builds_;
  ServerContext context_;
  std::optional<asio::ssl::context> tls_;  // with --tls-cert: every connection is TLS
  asio::ip::tcp::acceptor acceptor_;
  asio::steady_timer acceptRetry_;
  asio::signal_set signals_;
  std::uint16_t port_ = 0;
  std::uint64_t nextId_ = 1;
};

}  // namespace glint::server
