#pragma once

#include <string>
#include <thread>

#include "server/server.h"

namespace glint::server {

// A glintd inside this process, serving on a thread of its own (its I/O
// thread) until the object goes away: tests and the benchmark.
class BackgroundServer {
 public:
  explicit BackgroundServer(const ServerOptions& options) : server_(options), thread_([this] { server_.run(); }) {}
  ~BackgroundServer() {
    server_.stop();
    thread_.join();
  }
  BackgroundServer(const BackgroundServer&) = delete;
  BackgroundServer& operator=(const BackgroundServer&) = delete;

  std::string address() const { return "127.0.0.1:" + std::to_string(server_.port()); }
  std::uint16_t port() const { return server_.port(); }
  Server& server() { return server_; }

 private:
  Server server_;
  std::thread thread_;
};

}  // namespace glint::server
