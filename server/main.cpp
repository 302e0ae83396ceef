#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "common/error.h"
#include "common/heap_tuning.h"
#include "server/log.h"
#include "server/server.h"

namespace {

// Every connection is a descriptor: the soft limit (often 1024) is raised
// towards the hard one so that the pools the options allow can be filled.
void raiseDescriptorLimit(const glint::server::ServerOptions& o) {
  rlimit limit{};
  if (getrlimit(RLIMIT_NOFILE, &limit) != 0) return;
  const rlim_t wanted = static_cast<rlim_t>(o.maxClients) + static_cast<rlim_t>(o.maxWaiting) + 64;
  if (limit.rlim_cur >= wanted) return;
  limit.rlim_cur = std::min(wanted, limit.rlim_max);
  setrlimit(RLIMIT_NOFILE, &limit);
  if (limit.rlim_cur < wanted) {
    glint::server::logLine("only " + std::to_string(limit.rlim_cur) + " descriptors (ulimit -n) for " +
                           std::to_string(wanted - 64) + " connections: lower --max-waiting or raise the limit");
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace glint::server;
  glint::keepFreedMemoryForReuse();
  ServerOptions o;
  double maxMessageMb = static_cast<double>(o.maxMessageBytes >> 20);
  double cacheMb = static_cast<double>(o.cacheBytes >> 20);
  double sceneMb = static_cast<double>(o.maxSceneBytes >> 20);
  double memoryMb = static_cast<double>(o.maxMemoryBytes >> 20);
  double idleS = 300.0, readS = 30.0, handshakeS = 5.0;
  bool quiet = false;
  CLI::App app{"glintd: the Glint ray-trace server. Holds scenes (sent by clients as bytes, cached by\n"
               "content hash) and fills the masked tiles clients send, on a thread pool shared fairly\n"
               "between clients. SIGINT or SIGTERM stops it cleanly.",
               "glintd"};
  app.add_option("--listen", o.listen, "HOST:PORT to listen on (port 0: any free port)")->default_val(o.listen);
  app.add_option("--threads", o.threads, "Tracing threads; 0 = one per hardware thread")
      ->check(CLI::Range(0, 1024))
      ->default_val(0);
  app.add_option("--max-message-mb", maxMessageMb, "Largest message accepted from a client, in MiB")
      ->check(CLI::Range(1.0, 4095.0))
      ->default_val(maxMessageMb);
  app.add_option("--cache-mb", cacheMb, "Memory for cached scenes and their BVHs, in MiB (least recently used goes)")
      ->check(CLI::Range(1.0, 1e7))
      ->default_val(cacheMb);
  app.add_option("--max-scene-mb", sceneMb,
                 "Most memory one scene may hold once built (texels, meshes, BVH), in MiB; at most --cache-mb")
      ->check(CLI::Range(1.0, 1e7))
      ->default_val(sceneMb);
  app.add_option("--max-memory-mb", memoryMb,
                 "Memory for all scenes, cached and being built, in MiB; at least --cache-mb + --max-scene-mb")
      ->check(CLI::Range(2.0, 1e8))
      ->default_val(memoryMb);
  app.add_option("--max-clients", o.maxClients, "Clients served at once; more are refused with Busy at their Hello")
      ->check(CLI::Range(1, 100000))
      ->default_val(o.maxClients);
  app.add_option("--max-waiting", o.maxWaiting,
                 "Connections that have not said Hello yet; when full, the oldest is dropped")
      ->check(CLI::Range(1, 1000000))
      ->default_val(o.maxWaiting);
  app.add_option("--handshake-timeout", handshakeS, "Seconds a new connection has to say Hello")
      ->check(CLI::Range(0.1, 1e6))
      ->default_val(handshakeS);
  app.add_option("--idle-timeout", idleS, "Seconds a connection may sit with nothing to do")
      ->check(CLI::Range(0.1, 1e6))
      ->default_val(idleS);
  app.add_option("--read-timeout", readS, "Seconds to finish a message, or to read results")
      ->check(CLI::Range(0.1, 1e6))
      ->default_val(readS);
  app.add_flag("-q,--quiet", quiet, "No log lines");
  CLI11_PARSE(app, argc, argv);
  o.maxMessageBytes = static_cast<std::size_t>(maxMessageMb * 1048576.0);
  o.cacheBytes = static_cast<std::size_t>(cacheMb * 1048576.0);
  o.maxSceneBytes = static_cast<std::size_t>(sceneMb * 1048576.0);
  o.maxMemoryBytes = static_cast<std::size_t>(memoryMb * 1048576.0);
  o.idleTimeout = std::chrono::milliseconds(static_cast<long>(idleS * 1000));
  o.readTimeout = std::chrono::milliseconds(static_cast<long>(readS * 1000));
  o.handshakeTimeout = std::chrono::milliseconds(static_cast<long>(handshakeS * 1000));
  setLogging(!quiet);
  raiseDescriptorLimit(o);
  try {
    Server server(o);
    // One line on stdout that scripts can wait for; the port is the real one.
    const std::string host = o.listen.substr(0, o.listen.rfind(':'));
    std::printf("glintd: listening on %s:%u, %d threads\n", host.c_str(), server.port(), server.threads());
    std::fflush(stdout);
    server.run();
    logLine("stopped");
    return 0;
  } catch (const glint::InputError& e) {
    std::fprintf(stderr, "glintd: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glintd: internal error: %s\n", e.what());
    return 1;
  }
}
