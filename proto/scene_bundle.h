#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "common/scene/load_limits.h"
#include "common/scene/scene.h"
#include "common/scene/scene_budget.h"

namespace glint::proto {

using SceneHash = std::array<std::uint8_t, 32>;

// A scene as it travels: its JSON text and the bytes of every file it
// references, keyed by their normalised relative path. A server loads it
// from these bytes alone.
struct SceneBundle {
  std::string text;
  std::map<std::string, std::string> files;

  // SHA-256 over the text and each file (path and bytes), each part
  // preceded by its length, so that no two bundles share a hash by framing.
  SceneHash hash() const;
};

// SHA-256 of bytes: a file's identity on the wire (files are sent and kept
// by it).
SceneHash sha256(std::string_view bytes);

// A bundle's hash and each file's (in the order of bundle.files), computed
// once for every server it goes to.
struct BundleDigest {
  SceneHash scene{};
  std::vector<SceneHash> files;
};
BundleDigest digest(const SceneBundle& bundle);

// Loads a scene file from disk and collects the files it read into a bundle.
struct LoadedBundle {
  Scene scene;
  SceneBundle bundle;
};
LoadedBundle loadSceneBundle(const std::filesystem::path& path, const LoadLimits& limits = {});

// Loads a scene from a bundle, from memory only, counting what it will hold
// against `budget`.
Scene loadBundle(const SceneBundle& bundle, SceneBudget& budget);

std::string toHex(const SceneHash& hash);

}  // namespace glint::proto
