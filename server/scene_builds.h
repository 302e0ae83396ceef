#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "server/scene_builder.h"

namespace glint::server {

// glintd's scene builds, on a thread of their own so that a long or hostile
// build never holds a tracing thread: tiles of every client go on while a
// scene is parsed and its BVH built. A scene whose build is queued or running
// is built once for every client that uploads it meanwhile; a scene refused
// for what it is (not for memory that other builds held at the time, nor
// for bytes that were not its hash's) is refused again at once when it
// comes back, without a second parse.
class SceneBuilds {
 public:
  // Told on the builder thread; post to the I/O thread from there.
  using Done = std::function<void(const BuiltScene&)>;
  // Refusals remembered, the most recent.
  static constexpr std::size_t kRefusalsRemembered = 64;

  SceneBuilds(std::size_t maxSceneBytes, MemoryGauge& buildMemory);
  // Finishes the build running; the ones queued are dropped untold.
  ~SceneBuilds();
  SceneBuilds(const SceneBuilds&) = delete;
  SceneBuilds& operator=(const SceneBuilds&) = delete;

  void build(SceneJob job, Done done);
  // Builds run so far (a repeat that joined one, or was refused from memory,
  // is not one).
  std::size_t built() const;

 private:
  void run();
  void remember(const BuiltScene& built);

  std::size_t maxSceneBytes_;
  MemoryGauge& buildMemory_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<SceneJob> queue_;
  std::map<proto::SceneHash, std::vector<Done>> waiting_;  // queued or running, by scene
  std::map<proto::SceneHash, std::string> refused_;
  std::deque<proto::SceneHash> refusedOrder_;  // oldest first
  std::size_t built_ = 0;
  bool stopping_ = false;
  std::thread thread_;  // last: starts once the rest is made
};

}  // namespace glint::server
