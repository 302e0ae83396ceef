#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "common/error.h"
#include "common/heap_tuning.h"
#include "server/log.h"
#include "server/server.h"

int main(int argc, char** argv) {
  using namespace glint::server;
  glint::keepFreedMemoryForReuse();
  ServerOptions o;
  double maxMessageMb = static_cast<double>(o.maxMessageBytes >> 20);
  double cacheMb = static_cast<double>(o.cacheBytes >> 20);
  double idleS = 300.0, readS = 30.0;
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
  app.add_option("--max-clients", o.maxClients, "Clients served at once; more are refused with an error")
      ->check(CLI::Range(1, 100000))
      ->default_val(o.maxClients);
  app.add_option("--idle-timeout", idleS, "Seconds a connection may sit with nothing to do")
      ->check(CLI::Range(0.1, 1e6))
      ->default_val(idleS);
  app.add_option("--read-timeout", readS, "Seconds to finish a message, say Hello, or read results")
      ->check(CLI::Range(0.1, 1e6))
      ->default_val(readS);
  app.add_flag("-q,--quiet", quiet, "No log lines");
  CLI11_PARSE(app, argc, argv);
  o.maxMessageBytes = static_cast<std::size_t>(maxMessageMb * 1048576.0);
  o.cacheBytes = static_cast<std::size_t>(cacheMb * 1048576.0);
  o.idleTimeout = std::chrono::milliseconds(static_cast<long>(idleS * 1000));
  o.readTimeout = std::chrono::milliseconds(static_cast<long>(readS * 1000));
  o.handshakeTimeout = o.readTimeout;
  setLogging(!quiet);
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
