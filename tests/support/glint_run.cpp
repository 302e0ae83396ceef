#include "tests/support/glint_run.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "common/image/image_decode.h"
#include "common/scene/scene_budget.h"

namespace glint::test {

namespace {

GlintRun runToEnd(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  GlintRun run;
  if (!pipe) return run;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) run.output += buffer.data();
  const int raw = pclose(pipe);
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return run;
}

}  // namespace

GlintRun runGlint(const std::string& args, const std::string& prefix) {
  return runToEnd(prefix + std::string(GLINT_BIN) + " " + args + " 2>&1");
}

GlintRun runGlintd(const std::string& args) { return runToEnd(std::string(GLINTD_BIN) + " " + args + " 2>&1"); }

Image decodePngFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  SceneBudget budget;
  return decodeImage(bytes, path, budget);
}

}  // namespace glint::test
