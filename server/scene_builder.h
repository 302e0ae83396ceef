#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "common/render/prepared_scene.h"
#include "common/scene/scene_budget.h"
#include "proto/scene_bundle.h"

namespace glint::server {

// A scene a client uploaded, to be built on the pool.
struct SceneJob {
  proto::SceneHash hash{};
  std::shared_ptr<const proto::SceneBundle> bundle;  // copied out of the read buffer
};

// What came of it: the prepared scene (scene + BVH), or why not.
struct BuiltScene {
  proto::SceneHash hash{};
  std::shared_ptr<const PreparedScene> prepared;  // null on error
  std::string error;                              // names the JSON path or the limit; at most kMaxErrorBytes
  // Refused for what the scene of this hash is: the same upload would be
  // refused again. Not so when its bytes were not the hash's (another
  // upload of the hash may be the real scene) or when memory held by other
  // builds refused it (it may build later).
  bool lasting = false;
  double ms = 0.0;
};

// What one build may take: the memory the scene holds once built (also
// counted against the server's gauge of builds), and the time (zero: no
// limit), checked before each image, mesh and sphere is taken and before
// the BVH is built.
struct BuildLimits {
  std::size_t maxSceneBytes = LoadLimits{}.maxSceneBytes;
  std::chrono::milliseconds timeout{0};
};

// A refusal's text is cut to this many bytes (a JSON key it quotes may be
// megabytes long).
constexpr std::size_t kMaxErrorBytes = 4096;

// Loads a bundle from memory and builds its BVH: checks that the bytes match
// the hash, and counts what the scene will hold against `limits` and the
// server's gauge of scenes being built (held until the build is done).
// Never throws for bad input: errors come back in BuiltScene::error.
BuiltScene buildScene(const SceneJob& job, const BuildLimits& limits, MemoryGauge& buildMemory);

}  // namespace glint::server
