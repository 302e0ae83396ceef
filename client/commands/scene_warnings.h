#pragma once

#include <cstdio>
#include <string>

#include "common/scene/scene.h"

namespace glint {

// The loader's warnings (docs/scene-format.md), one line each on stderr,
// prefixed with the scene file, as every command prints them after loading.
inline void printSceneWarnings(const std::string& sceneFile, const Scene& scene) {
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s: %s\n", sceneFile.c_str(), w.c_str());
}

}  // namespace glint
