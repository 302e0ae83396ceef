#include "server/log.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <mutex>

#include "common/base/printable.h"

namespace glint::server {
namespace {

std::mutex gMutex;
std::atomic<bool> gEnabled{true};

}  // namespace

void setLogging(bool enabled) { gEnabled = enabled; }

void logLine(const std::string& line) {
  if (!gEnabled) return;
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", &tm);
  std::lock_guard lock(gMutex);
  std::fprintf(stderr, "%s.%03dZ glintd: %s\n", stamp, static_cast<int>(ms), printable(line).c_str());
}

}  // namespace glint::server
