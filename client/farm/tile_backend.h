#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "common/geometry/bvh.h"
#include "common/render/irradiance_field.h"
#include "common/render/prepared_scene.h"
#include "common/base/thread_pool.h"
#include "common/render/tile_service.h"
#include "proto/scene_bundle.h"
#include "proto/tls.h"

namespace glint {

class DistributedTileService;

// Where a command's tiles are traced, chosen from its options: in process
// (the scene prepared here with the chosen BVH builder, on a thread pool) or
// through one or many glintd (which build their own BVH, so --bvh is refused
// there). render, view and the benchmark all get their service here.
// Owns what the service needs; the scene stays readable for the raster pass.
// The options that send tiles to glintd (render and view share them).
struct RemoteOptions {
  std::vector<std::string> servers;  // --server values (HOST:PORT[,...])
  std::string serverFile;            // --server-file: more servers, read again when it changes
  double stallTimeoutS = 2.0;        // --stall-timeout
  double sceneTimeoutS = 120.0;      // --scene-timeout
  proto::TlsFiles tls;               // --tls-ca, --tls-cert, --tls-key

  // Through servers; neither option: in process.
  bool any() const { return !servers.empty() || !serverFile.empty(); }
};

// The service over the servers the options name (resolved, TLS as given),
// bound to `bundle`; `awaitServer` as DistributedSettings::awaitOne.
std::unique_ptr<DistributedTileService> connectServers(const RemoteOptions& remote, const proto::SceneBundle& bundle,
                                                       bool awaitServer = true);

class TileBackend {
 public:
  struct Options {
    RemoteOptions remote;
    std::optional<BvhBuilder> bvh;
    bool awaitServer = true;  // wait for a server to be ready (view does not)
    // Fill the scene's irradiance field (its tracing.field settings, which
    // it must have) once, for the hybrid frame under path transport, in
    // process or in batches on the servers, and trace with it; told, never
    // concurrently, how many of its probes are filled.
    bool field = false;
    std::function<void(int done, int total)> fieldProgress = {};
  };
  // What filling the field took.
  struct FieldFill {
    double ms = 0.0;
    RayStats rays;
  };

  // Prepares the scene or connects and uploads it; throws InputError.
  TileBackend(const Options& options, proto::LoadedBundle loaded);
  ~TileBackend();
  TileBackend(const TileBackend&) = delete;
  TileBackend& operator=(const TileBackend&) = delete;

  TileService& service() { return *service_; }
  // The servers' service; nullptr in process.
  DistributedTileService* distributed() const { return distributed_; }
  const Scene& scene() const;
  // In process: the prepared scene and its pool (for linear renders);
  // nullptr through servers.
  const PreparedScene* prepared() const { return prepared_.get(); }
  ThreadPool* pool() { return pool_; }
  // The irradiance field the tiles are traced with (Options::field); none
  // otherwise.
  const IrradianceField* field() const { return field_ ? &*field_ : nullptr; }
  const FieldFill& fieldFill() const { return fieldFill_; }
  // "4 threads", "server HOST:PORT" or "3 servers", for summaries.
  std::string where() const;

 private:
  void fillOnServers(const std::function<void(int, int)>& progress);

  DistributedTileService* distributed_ = nullptr;  // service_, when it is one
  proto::LoadedBundle loaded_;
  std::unique_ptr<PreparedScene> prepared_;  // in process only
  ThreadPool* pool_ = nullptr;               // the compute pool, in process only
  std::optional<IrradianceField> field_;
  FieldFill fieldFill_;
  std::unique_ptr<TileService> service_;
};

}  // namespace glint
