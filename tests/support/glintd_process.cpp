#include "tests/support/glintd_process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace glint::server::test {

GlintdProcess::GlintdProcess(const std::vector<std::string>& args) {
  std::vector<std::string> all = {GLINTD_BIN, "--listen", "127.0.0.1:0", "--quiet", "--ready-fd", "3"};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  int ready[2];
  if (pipe2(ready, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");  // only the dup2s reach glintd
  char logName[] = "/tmp/glintd-printed-XXXXXX";
  printed_ = mkostemp(logName, O_CLOEXEC);
  if (printed_ < 0) throw std::runtime_error("mkstemp failed");
  unlink(logName);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, ready[1], 3);
  posix_spawn_file_actions_adddup2(&actions, printed_, 1);
  posix_spawn_file_actions_adddup2(&actions, printed_, 2);
  const int spawned = posix_spawn(&pid_, GLINTD_BIN, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(ready[1]);
  if (spawned != 0) {
    close(ready[0]);
    throw std::runtime_error(std::string("cannot start glintd: ") + std::strerror(spawned));
  }
  FILE* readyLine = fdopen(ready[0], "r");
  char line[256] = {};
  const bool read = std::fgets(line, sizeof line, readyLine) != nullptr;
  std::fclose(readyLine);  // glintd closes its end once it has written the line
  unsigned port = 0;
  if (!read || std::sscanf(line, "glintd: listening on 127.0.0.1:%u", &port) != 1) {
    stop(SIGKILL);
    throw std::runtime_error("glintd did not start: " + std::string(line) + printed());
  }
  port_ = static_cast<std::uint16_t>(port);
  listeningLine_ = line;
}

std::string GlintdProcess::printed() const {
  std::string all;
  char buffer[4096];
  off_t at = 0;
  for (ssize_t n; (n = pread(printed_, buffer, sizeof buffer, at)) > 0; at += n) all.append(buffer, static_cast<std::size_t>(n));
  return all;
}

GlintdProcess::~GlintdProcess() {
  if (status_ < 0) stop(SIGKILL);
  close(printed_);
}

bool GlintdProcess::running() {
  if (status_ >= 0) return false;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) == pid_) status_ = status;
  return status_ < 0;
}

int GlintdProcess::stop(int signal) {
  if (!running()) return status_;
  kill(pid_, signal);
  const auto start = std::chrono::steady_clock::now();
  while (running() && std::chrono::steady_clock::now() - start < std::chrono::seconds(10)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (running()) {
    kill(pid_, SIGKILL);
    waitpid(pid_, &status_, 0);
    return -1;
  }
  return status_;
}

long GlintdProcess::statusKb(const char* field) const {
  std::ifstream in("/proc/" + std::to_string(pid_) + "/status");
  std::string key;
  long kb = -1;
  while (in >> key) {
    if (key == field) {
      in >> kb;
      break;
    }
  }
  return kb;
}

// /proc/net/tcp: "sl local_address rem_address st tx_queue:rx_queue ...",
// addresses and queues in hex.
long GlintdProcess::unreadBytes() const {
  std::ifstream in("/proc/net/tcp");
  std::string line;
  std::getline(in, line);  // the heading
  long unread = 0;
  while (std::getline(in, line)) {
    char local[64], remote[64], queues[64];
    unsigned state = 0;
    if (std::sscanf(line.c_str(), "%*s %63s %63s %x %63s", local, remote, &state, queues) != 4) continue;
    const char* port = std::strchr(local, ':');
    if (!port || std::strtoul(port + 1, nullptr, 16) != port_) continue;
    const char* rx = std::strchr(queues, ':');
    if (rx) unread += static_cast<long>(std::strtoul(rx + 1, nullptr, 16));
  }
  return unread;
}

bool GlintdProcess::awaitAllRead(int seconds) const {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  while (unreadBytes() > 0) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

int GlintdProcess::openDescriptors() const {
  int n = 0;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator("/proc/" + std::to_string(pid_) + "/fd", ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
    ++n;
  }
  return n;
}

}  // namespace glint::server::test
