#pragma once

#include <string>

#include "common/image/texel_image.h"

namespace glint::test {

// What the real `glint` or `glintd` program did: its exit status (-1 when
// it did not exit normally) and what it printed, stdout and stderr together.
struct GlintRun {
  int status = -1;
  std::string output;
};

// Runs `glint ARGS` as a user would, with `prefix` before it (onDisplay()).
GlintRun runGlint(const std::string& args, const std::string& prefix = "");
// Runs `glintd ARGS` to its end (for arguments it refuses, or --help).
GlintRun runGlintd(const std::string& args);

// A PNG the program wrote, decoded.
Image decodePngFile(const std::string& path);

}  // namespace glint::test
