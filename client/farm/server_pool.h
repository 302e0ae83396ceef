#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <asio.hpp>
#include <asio/ssl.hpp>

#include "client/farm/farm_server.h"
#include "proto/scene_bundle.h"
#include "proto/tls.h"

namespace glint {

// The servers a client renders through, a record of each (FarmServer) with
// its link, on one io_context: all connected at once (over TLS where `tls` names files), each
// lost one tried again after a backoff of 1, 2, 4 ... at most 30 s, each
// with its report for the frame. Between frames the set may change
// (adopt()): a server that leaves is told Goodbye and never tried again, but
// keeps its index and record, which it takes again if it comes back. Its links tell `listener`, which tells the
// pool (ready(), failed()) before it does anything else.
class ServerPool {
 public:
  // Throws InputError for TLS files that cannot be used.
  ServerPool(asio::io_context& io, std::vector<ServerAddress> addresses, const proto::SceneBundle& bundle,
             const proto::BundleDigest& digest, const LinkTimeouts& timeouts, const proto::TlsFiles& tls,
             LinkListener& listener);
  ServerPool(const ServerPool&) = delete;
  ServerPool& operator=(const ServerPool&) = delete;

  // Each server's link says Goodbye (the io_context then writes them).
  void closeAll();
  // Between frames: the servers of `wanted` not members join (connected
  // now), the members not in it leave (Goodbye); `frame` is the report
  // that says so.
  void adopt(const std::vector<ServerAddress>& wanted, int frame);
  // Servers lost earlier whose backoff has ended are connected again.
  void retryLost();
  // The earliest retry of a server that answered Busy, if it comes within
  // `patience` of its first Busy (a busy server is worth waiting for that
  // long: --scene-timeout).
  std::optional<std::chrono::steady_clock::time_point> nextBusyRetry(std::chrono::milliseconds patience) const;
  void ready(std::size_t index);
  void failed(std::size_t index, const LinkFailure& failure);

  std::size_t size() const { return servers_.size(); }
  FarmServer& operator[](std::size_t index) { return servers_[index]; }
  const FarmServer& operator[](std::size_t index) const { return servers_[index]; }
  std::vector<FarmServer>& all() { return servers_; }
  const std::vector<FarmServer>& all() const { return servers_; }
  // Ready and a member: gets tiles.
  bool serving(std::size_t index) const { return servers_[index].member && servers_[index].link->ready(); }
  std::size_t members() const;
  std::size_t up() const;
  bool anyConnecting() const;
  bool anyUploaded() const;
  int threadsUp() const;
  // One line per server: its state and why.
  std::string states() const;

 private:
  void connect(std::size_t index);

  asio::io_context& io_;
  const proto::SceneBundle& bundle_;
  const proto::BundleDigest& digest_;
  LinkTimeouts timeouts_;
  std::optional<asio::ssl::context> tls_;
  LinkListener& listener_;
  std::vector<FarmServer> servers_;
};

}  // namespace glint
