#pragma once

#include <chrono>
#include <cstddef>
#include <string>

#include "proto/framing.h"
#include "proto/tls.h"

namespace glint::server {

// Everything glintd can be told, with its defaults.
struct ServerOptions {
  std::string listen = "127.0.0.1:7878";  // loopback unless the user says otherwise
  int threads = 0;                         // tracing threads; 0 = one per hardware thread
  // Trace on the process's compute pool (glintd: its one pool, sized by
  // --threads, that BVH builds and decoders share) rather than on a pool of
  // the server's own (a test's servers in one process).
  bool computePool = false;
  std::size_t maxMessageBytes = proto::kDefaultMaxMessageBytes;
  // Before Hello a peer is a stranger: its messages (a Hello is under 100
  // bytes) may be no larger than this.
  static constexpr std::size_t kMaxHandshakeMessageBytes = 4096;
  // Memory for scenes, sized for a 24 GiB host: the cache of built scenes, the
  // most one scene may hold once built (texels, meshes, BVH; at most the
  // cache), and the whole (the cache and the scenes being built at once).
  std::size_t cacheBytes = std::size_t{4} << 30;
  std::size_t maxSceneBytes = std::size_t{2} << 30;
  std::size_t maxMemoryBytes = std::size_t{12} << 30;
  int maxClients = 64;  // clients that said Hello
  // Connections that have not said Hello yet: a pool of their own, oldest
  // dropped first when full, so that silent connections never lock out clients.
  int maxWaiting = 512;
  // A connection must say Hello within this; a message started must be
  // finished within readTimeout.
  std::chrono::milliseconds handshakeTimeout{5'000};
  std::chrono::milliseconds readTimeout{30'000};
  // A scene's build (its files decoded, the BVH built) past this is refused.
  std::chrono::milliseconds buildTimeout{30'000};
  // A connection with nothing to read, write or compute is closed after this.
  std::chrono::milliseconds idleTimeout{300'000};
  // Results a client leaves unread beyond this many bytes close its connection.
  std::size_t maxQueuedBytes = std::size_t{256} << 20;
  bool handleSignals = true;  // SIGINT and SIGTERM stop the server
  // Mutual TLS: this server's certificate and key, and the CA that signs its
  // clients' certificates (all three, or none).
  proto::TlsFiles tls;
  // Without TLS glintd listens on loopback only, unless told this.
  bool insecure = false;
};

}  // namespace glint::server
