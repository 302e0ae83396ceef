#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/base/build_identity.h"
#include "common/base/compute_pool.h"
#include "common/base/error.h"
#include "common/base/heap_tuning.h"
#include "common/base/nearest_word.h"
#include "proto/endpoint.h"
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

// An option in MiB that sets a byte count; its default is the count's.
void addMebibytes(CLI::App& app, const char* name, std::size_t& bytes, const char* help, double lo, double hi) {
  app.add_option_function<double>(
         name, [&bytes](double mb) { bytes = static_cast<std::size_t>(mb * 1048576.0); }, help)
      ->check(CLI::Range(lo, hi))
      ->default_str(std::to_string(bytes >> 20));
}

// An option in seconds that sets a duration; its default is the duration's.
void addSeconds(CLI::App& app, const char* name, std::chrono::milliseconds& duration, const char* help) {
  app.add_option_function<double>(
         name, [&duration](double s) { duration = std::chrono::milliseconds(static_cast<long>(s * 1000)); }, help)
      ->check(CLI::Range(0.1, 1e6))
      ->default_str(CLI::detail::to_string(static_cast<double>(duration.count()) / 1000.0));
}

// An address glintd can listen on, checked while the options are read so
// that a bad one is a usage error; CLI11 puts the option's name before the
// words.
std::string listenProblem(const std::string& address) {
  const std::string option = "--listen";
  try {
    glint::proto::parseEndpoint(address, option);
    return {};
  } catch (const glint::InputError& e) {
    return std::string(e.what()).substr(option.size() + 1);
  }
}

// How glintd says where it listens: on stdout unless --quiet, and on
// --ready-fd's descriptor (for scripts and supervisors) either way.
struct Announce {
  bool quiet = false;
  int readyFd = -1;
};

void declareOptions(CLI::App& app, glint::server::ServerOptions& o, Announce& announce) {
  app.add_option("--listen", o.listen, "HOST:PORT to listen on (port 0: any free port)")
      ->check(listenProblem, "HOST:PORT")
      ->default_val(o.listen);
  app.add_option("--threads", o.threads, "Tracing threads; 0 = one per hardware thread")
      ->check(CLI::Range(0, 1024))
      ->default_val(0);
  addMebibytes(app, "--max-message-mb", o.maxMessageBytes, "Largest message accepted from a client, in MiB", 1.0,
               4095.0);
  addMebibytes(app, "--cache-mb", o.cacheBytes,
               "Memory for cached scenes and their BVHs, in MiB (least recently used goes)", 1.0, 1e7);
  addMebibytes(app, "--max-scene-mb", o.maxSceneBytes,
               "Most memory one scene may hold once built (texels, meshes, BVH), in MiB; at most --cache-mb; also "
               "the most uploaded files kept (each one file's limit)",
               1.0,
               1e7);
  addMebibytes(app, "--max-memory-mb", o.maxMemoryBytes,
               "Memory for all scenes, cached, being built and uploading, in MiB; at least --cache-mb + 2 x "
               "--max-scene-mb",
               2.0,
               1e8);
  app.add_option("--max-clients", o.maxClients, "Clients served at once; more are refused with Busy at their Hello")
      ->check(CLI::Range(1, 100000))
      ->default_val(o.maxClients);
  app.add_option("--max-waiting", o.maxWaiting, "Connections that have not said Hello yet; when full, the oldest is dropped")
      ->check(CLI::Range(1, 1000000))
      ->default_val(o.maxWaiting);
  addSeconds(app, "--handshake-timeout", o.handshakeTimeout, "Seconds a new connection has to say Hello");
  addSeconds(app, "--idle-timeout", o.idleTimeout, "Seconds a connection may sit with nothing to do");
  addSeconds(app, "--read-timeout", o.readTimeout, "Seconds to finish a message, or to read results");
  addSeconds(app, "--build-timeout", o.buildTimeout,
             "Seconds a scene's build may take (its files decoded, its BVH built); past it the scene is refused");
  app.add_option("--tls-cert", o.tls.cert, "This server's certificate (PEM) for TLS 1.3; with --tls-key and "
                 "--tls-client-ca every connection is TLS")
      ->envname("GLINTD_TLS_CERT");
  app.add_option("--tls-key", o.tls.key, "The private key of --tls-cert (PEM)")->envname("GLINTD_TLS_KEY");
  app.add_option("--tls-client-ca", o.tls.ca,
                 "CA certificate (PEM) that clients' certificates must chain to; others are refused")
      ->envname("GLINTD_TLS_CLIENT_CA");
  app.add_flag("--insecure", o.insecure,
               "Listen on a non-loopback address without TLS (anyone who reaches it can use glintd)");
  app.add_flag("-q,--quiet", announce.quiet, "Print nothing but errors (not even the listening line)");
  app.add_option("--ready-fd", announce.readyFd,
                 "Once listening, write the listening line to this open descriptor and close it (3: '3>file')")
      ->check(CLI::Range(1, 1 << 20));
}

// The first option glintd does not have, with the nearest it has; else
// CLI11's words for what is wrong.
std::string usageProblem(const CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  std::vector<std::string> known;
  for (const CLI::Option* option : app.get_options()) {
    for (const std::string& name : option->get_lnames()) known.push_back("--" + name);
    for (const std::string& name : option->get_snames()) known.push_back("-" + name);
  }
  const std::string unknown = glint::unknownOption("glintd", std::vector<std::string>(argv + 1, argv + argc), known);
  return unknown.empty() ? e.what() : unknown;
}

// The descriptor --ready-fd names is open for writing (a usage error
// otherwise, before anything is bound).
void checkReadyFd(int fd) {
  if (fd < 0) return;
  const int flags = fcntl(fd, F_GETFL);
  if (flags < 0 || (flags & O_ACCMODE) == O_RDONLY) {
    throw glint::UsageError("--ready-fd " + std::to_string(fd) +
                            ": not a descriptor open for writing (start glintd with e.g. '3>ready.txt')");
  }
}

// The listening line on stdout and on --ready-fd's descriptor.
void announceListening(const Announce& a, const std::string& line) {
  if (!a.quiet) {
    std::fputs(line.c_str(), stdout);
    std::fflush(stdout);
  }
  if (a.readyFd < 0) return;
  if (write(a.readyFd, line.data(), line.size()) < 0) glint::server::logLine("--ready-fd: cannot write the line");
  if (a.readyFd > 2) close(a.readyFd);
}

// How clients reach it, for the line scripts wait for.
std::string transport(const glint::server::ServerOptions& o) {
  return o.tls.any() ? "TLS 1.3, client certificates required" : "no TLS";
}

constexpr int kUsageError = 2;
constexpr const char* kHelpHint = "(the options: glintd --help)";

}  // namespace

int main(int argc, char** argv) {
  using namespace glint::server;
  glint::keepFreedMemoryForReuse();
  ServerOptions o;
  Announce announce;
  CLI::App app{"glintd: the Glint ray-trace server. Holds scenes (sent by clients as bytes, cached by\n"
               "content hash) and fills the masked tiles clients send, on a thread pool shared fairly\n"
               "between clients. SIGINT or SIGTERM stops it cleanly.",
               "glintd"};
  declareOptions(app, o, announce);
  app.set_version_flag("--version", "glintd 0.1.0 (" + glint::buildIdentity() + ")");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help and --version print and are not errors
    std::fprintf(stderr, "glintd: error: %s %s\n", usageProblem(app, e, argc, argv).c_str(), kHelpHint);
    return kUsageError;  // as shells expect
  }
  setLogging(!announce.quiet);
  raiseDescriptorLimit(o);
  glint::setComputeThreads(o.threads);
  o.computePool = true;
  try {
    checkReadyFd(announce.readyFd);
    Server server(o);
    // The line scripts wait for; the port is the real one.
    const std::string host = o.listen.substr(0, o.listen.rfind(':'));
    announceListening(announce, "glintd: listening on " + host + ":" + std::to_string(server.port()) + ", " +
                                    std::to_string(server.threads()) + (server.threads() == 1 ? " thread, " : " threads, ") +
                                    transport(o) + "\n");
    server.run();
    logLine("stopped");
    return 0;
  } catch (const glint::UsageError& e) {
    std::fprintf(stderr, "glintd: error: %s %s\n", e.what(), kHelpHint);
    return kUsageError;
  } catch (const glint::InputError& e) {
    std::fprintf(stderr, "glintd: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glintd: internal error: %s\n", e.what());
    return 1;
  }
}
