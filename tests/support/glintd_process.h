#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace glint::server::test {

// A real glintd process listening on a free loopback port, for tests that
// must see what a remote client can do to the server process itself (a crash,
// its memory). Killed, if still running, when the object goes away.
class GlintdProcess {
 public:
  // Starts glintd with `--listen 127.0.0.1:0 --quiet --ready-fd 3` and
  // `args`, and waits for its "listening on" line on descriptor 3; what it
  // prints on stdout and stderr goes to a file of its own (printed()).
  explicit GlintdProcess(const std::vector<std::string>& args = {});
  ~GlintdProcess();
  GlintdProcess(const GlintdProcess&) = delete;
  GlintdProcess& operator=(const GlintdProcess&) = delete;

  pid_t pid() const { return pid_; }
  std::uint16_t port() const { return port_; }
  std::string address() const { return "127.0.0.1:" + std::to_string(port_); }
  // The line it said it was listening on ("glintd: listening on ...").
  const std::string& listeningLine() const { return listeningLine_; }
  // All it has printed on stdout and stderr so far.
  std::string printed() const;
  // True while the process has not exited.
  bool running();
  // Resident memory now and at its peak, in KiB (/proc/PID/status VmRSS, VmHWM).
  long residentKb() const { return statusKb("VmRSS:"); }
  long peakResidentKb() const { return statusKb("VmHWM:"); }
  // Open file descriptors (/proc/PID/fd).
  int openDescriptors() const;
  // Bytes that arrived on its connections and that it has not read yet
  // (the receive queues of /proc/net/tcp whose local port is its own).
  long unreadBytes() const;
  // Waits up to `seconds` until it has read all that arrived (on loopback,
  // what a client wrote has arrived when its write returns); false if not.
  bool awaitAllRead(int seconds = 10) const;
  // Sends `signal` and waits up to 10 s for the exit; the wait status
  // (WIFEXITED ...), or -1 when it had to be killed.
  int stop(int signal);

 private:
  long statusKb(const char* field) const;

  pid_t pid_ = 0;
  std::uint16_t port_ = 0;
  std::string listeningLine_;
  int status_ = -1;  // set once reaped
  int printed_ = -1;  // the unlinked file of its stdout and stderr
};

}  // namespace glint::server::test
