#include "client/farm/tile_backend.h"

#include "client/farm/distributed_tile_service.h"
#include "common/base/compute_pool.h"
#include "common/base/error.h"
#include "common/base/timing.h"
#include "common/render/field_probes.h"

namespace glint {

std::unique_ptr<DistributedTileService> connectServers(const RemoteOptions& remote, const proto::SceneBundle& bundle,
                                                       bool awaitServer) {
  DistributedSettings settings;
  settings.stallTimeout = std::chrono::milliseconds(static_cast<long>(remote.stallTimeoutS * 1000.0));
  settings.timeouts.scene = std::chrono::milliseconds(static_cast<long>(remote.sceneTimeoutS * 1000.0));
  settings.awaitOne = awaitServer;
  settings.tls = remote.tls;
  ServerSource source(remote.servers, remote.serverFile, ServerSource::Clock::now());
  return std::make_unique<DistributedTileService>(std::move(source), bundle, settings);
}

TileBackend::TileBackend(const Options& options, proto::LoadedBundle loaded) : loaded_(std::move(loaded)) {
  const RemoteOptions& remote = options.remote;
  if (!remote.any() && remote.tls.any()) {
    throw UsageError("--tls-ca, --tls-cert and --tls-key secure the connections to glintd; give --server");
  }
  if (remote.any()) {
    if (options.bvh) {
      throw UsageError("--bvh: a glintd builds the BVH of the scenes it holds itself (SAH); --bvh applies to "
                       "in-process rendering");
    }
    auto service = connectServers(remote, loaded_.bundle, options.awaitServer);
    distributed_ = service.get();
    service_ = std::move(service);
    if (options.field) fillOnServers(options.fieldProgress);
    return;
  }
  BvhSettings bvh;
  bvh.builder = options.bvh.value_or(bvh.builder);
  prepared_ = std::make_unique<PreparedScene>(std::move(loaded_.scene), bvh);
  pool_ = &computePool();
  if (options.field) {
    const FrameSettings& frame = prepared_->scene().frame;
    const Clock::time_point start = Clock::now();
    field_.emplace(buildField(*prepared_, frame, *frame.tracing.field, fieldFill_.rays, options.fieldProgress));
    fieldFill_.ms = msSince(start);
  }
  service_ = std::make_unique<LocalTileService>(*prepared_, *pool_, field());
}

// The field in batches the servers trace, then sent to each for the frames.
void TileBackend::fillOnServers(const std::function<void(int, int)>& progress) {
  const FrameSettings& frame = loaded_.scene.frame;
  const Clock::time_point start = Clock::now();
  const FieldGrid grid(loaded_.scene.geometry.bounds(), *frame.tracing.field);
  if (progress) {
    distributed_->onTraced([&](std::size_t probes) { progress(static_cast<int>(probes), grid.probeCount()); });
  }
  field_.emplace(distributed_->fillField(frame, loaded_.scene.geometry.bounds(), *frame.tracing.field));
  distributed_->onTraced({});
  fieldFill_.ms = msSince(start);
  for (const ServerReport& s : distributed_->fieldReport().servers) fieldFill_.rays += s.rays;
  distributed_->useField(&*field_);
}

TileBackend::~TileBackend() = default;

const Scene& TileBackend::scene() const { return prepared_ ? prepared_->scene() : loaded_.scene; }

std::string TileBackend::where() const {
  if (pool_) return std::to_string(pool_->size()) + (pool_->size() == 1 ? " thread" : " threads");
  const DistributionReport& report = distributed_->lastFrame();
  if (distributed_->serverCount() == 1 && !report.servers.empty()) return "server " + report.servers[0].address;
  return std::to_string(distributed_->serverCount()) + " servers";
}

}  // namespace glint
