#pragma once

#include <chrono>
#include <cstddef>
#include <string>

#include "proto/framing.h"

namespace glint::server {

// Everything glintd can be told, with its defaults.
struct ServerOptions {
  std::string listen = "127.0.0.1:7878";  // loopback unless the user says otherwise
  int threads = 0;                         // tracing threads; 0 = one per hardware thread
  std::size_t maxMessageBytes = proto::kDefaultMaxMessageBytes;
  std::size_t cacheBytes = std::size_t{1} << 30;
  int maxClients = 64;
  // A client must say Hello within this, and finish a message it started.
  std::chrono::milliseconds handshakeTimeout{10'000};
  std::chrono::milliseconds readTimeout{30'000};
  // A connection with nothing to read, write or compute is closed after this.
  std::chrono::milliseconds idleTimeout{300'000};
  // Results a client leaves unread beyond this many bytes close its connection.
  std::size_t maxQueuedBytes = std::size_t{256} << 20;
  bool handleSignals = true;  // SIGINT and SIGTERM stop the server
};

}  // namespace glint::server
