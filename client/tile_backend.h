#pragma once

#include <memory>
#include <optional>
#include <string>

#include "common/bvh.h"
#include "common/prepared_scene.h"
#include "common/thread_pool.h"
#include "common/tile_service.h"
#include "proto/scene_bundle.h"

namespace glint {

class RemoteTileService;

// Where a command's tiles are traced, chosen from its options: in process
// (the scene prepared here with the chosen BVH builder, on a thread pool) or
// through a glintd (which builds its own BVH, so --bvh is refused there).
// Owns what the service needs; the scene stays readable for the raster pass.
class TileBackend {
 public:
  struct Options {
    std::string server;  // HOST:PORT of a glintd; "" traces in process
    int threads = 0;     // in process; 0: every hardware thread
    std::optional<BvhBuilder> bvh;
  };

  // Prepares the scene or connects and uploads it; throws InputError.
  TileBackend(const Options& options, proto::LoadedBundle loaded);
  ~TileBackend();
  TileBackend(const TileBackend&) = delete;
  TileBackend& operator=(const TileBackend&) = delete;

  TileService& service() { return *service_; }
  const Scene& scene() const;
  // "4 threads" or "server HOST:PORT", for summaries.
  std::string where() const;

 private:
  std::string server_;
  proto::LoadedBundle loaded_;
  std::unique_ptr<PreparedScene> prepared_;  // in process only
  std::unique_ptr<ThreadPool> pool_;         // in process only
  std::unique_ptr<TileService> service_;
};

}  // namespace glint
