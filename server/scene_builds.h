#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "common/base/thread_pool.h"
#include "server/scene_builder.h"

namespace glint::server {

// glintd's scene builds, on a pool of their own so that a long or hostile
// build never holds a tracing thread: tiles of every client go on while a
// scene is parsed and its BVH built; several builds run at once, so that
// one long build does not hold every new scene back (a client has at most
// one build queued or running: Session). A scene whose build is queued or
// running is built once for every client that uploads it meanwhile; a
// scene refused for what it is (not for memory that other builds held at
// the time, nor for bytes that were not its hash's) is refused again at
// once when it comes back, without a second parse.
class SceneBuilds {
 public:
  // Told on the builder thread; post to the I/O thread from there.
  using Done = std::function<void(const BuiltScene&)>;
  // Refusals remembered, the most recent.
  static constexpr std::size_t kRefusalsRemembered = 64;
  // The builds glintd runs at once beside `tracing` tracing threads: as many,
  // at most kMaxThreads (each may hold up to --max-scene-mb of the builds'
  // memory). Builds come seldom and tiles wait for them; the costliest
  // image a client may send decodes for about 3 s, and four such uploads
  // queued before a new scene delayed it by 11 s on one build thread.
  static constexpr int kMaxThreads = 4;
  static int threadsBeside(int tracing) { return std::clamp(tracing, 1, kMaxThreads); }

  // `threads` builds run at once (at least one), drawing on buildMemory.
  SceneBuilds(const BuildLimits& limits, MemoryGauge& buildMemory, int threads = 1);
  // Finishes the builds running; the ones queued are dropped untold.
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

  BuildLimits limits_;
  MemoryGauge& buildMemory_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<SceneJob> queue_;
  std::map<proto::SceneHash, std::vector<Done>> waiting_;  // queued or running, by scene
  std::map<proto::SceneHash, std::string> refused_;
  std::deque<proto::SceneHash> refusedOrder_;  // oldest first
  std::size_t built_ = 0;
  bool stopping_ = false;
  ThreadPool builders_;  // last: each runs run() until stopping_, once the rest is made
};

}  // namespace glint::server
