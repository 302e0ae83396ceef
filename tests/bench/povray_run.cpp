#include "tests/bench/povray_run.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>

#include "tests/bench/bench_timing.h"

namespace glint::bench {
namespace {

// The seconds on a statistics line such as "Trace Time:  0 hours  0 minutes
// 0 seconds (0.382 seconds)"; 0 when the line says none ("No radiosity"),
// negative when there is no such line.
double statisticSeconds(const std::string& statistics, const std::string& name) {
  const std::size_t line = statistics.find(name);
  if (line == std::string::npos) return -1.0;
  const std::size_t end = statistics.find('\n', line);
  const std::size_t open = statistics.find('(', line);
  if (open == std::string::npos || open > end) return 0.0;
  return std::strtod(statistics.c_str() + open + 1, nullptr);
}

}  // namespace

bool povrayInstalled() { return std::system("command -v povray > /dev/null 2>&1") == 0; }

PovrayRun runPovray(const std::filesystem::path& pov, const std::filesystem::path& out, int width, int height,
                    const std::string& options) {
  const std::string cmd = "povray +I" + pov.string() + " +O" + out.string() + " +W" + std::to_string(width) +
                          " +H" + std::to_string(height) + " " + options + " +WT2 -D -GR -V +FN 2>&1";
  std::string statistics;
  PovrayRun run;
  run.processMs = medianMs(1, [&] {
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return;
    std::array<char, 4096> buffer;
    for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) {
      statistics.append(buffer.data(), n);
    }
    if (pclose(pipe) != 0) statistics.clear();
  });
  const double trace = statisticSeconds(statistics, "Trace Time:");
  if (trace <= 0.0) return {};
  run.renderMs = 1000.0 * (trace + std::max(0.0, statisticSeconds(statistics, "Radiosity Time:")));
  return run;
}

}  // namespace glint::bench
