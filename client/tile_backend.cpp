#include "client/tile_backend.h"

#include "client/remote_tile_service.h"
#include "common/error.h"

namespace glint {

TileBackend::TileBackend(const Options& options, proto::LoadedBundle loaded)
    : server_(options.server), loaded_(std::move(loaded)) {
  if (!server_.empty()) {
    if (options.bvh) {
      throw InputError("--bvh: a glintd builds the BVH of the scenes it holds itself (SAH); --bvh applies to "
                       "in-process rendering");
    }
    service_ = std::make_unique<RemoteTileService>(server_, loaded_.bundle);
    return;
  }
  BvhSettings bvh;
  bvh.builder = options.bvh.value_or(bvh.builder);
  prepared_ = std::make_unique<PreparedScene>(std::move(loaded_.scene), bvh);
  pool_ = std::make_unique<ThreadPool>(resolveThreadCount(options.threads));
  service_ = std::make_unique<LocalTileService>(*prepared_, *pool_);
}

TileBackend::~TileBackend() = default;

const Scene& TileBackend::scene() const { return prepared_ ? prepared_->scene() : loaded_.scene; }

std::string TileBackend::where() const {
  return pool_ ? std::to_string(pool_->size()) + " threads" : "server " + server_;
}

}  // namespace glint
