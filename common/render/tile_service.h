#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "common/render/irradiance_field.h"
#include "common/render/prepared_scene.h"
#include "common/render/ray_stats.h"
#include "common/scene/scene.h"
#include "common/base/thread_pool.h"
#include "common/render/tile.h"

namespace glint {

// One tile of a frame to fill: a rectangle and its mask (empty: every pixel).
struct TileJob {
  TileRect rect;
  std::vector<std::uint8_t> mask;
};

// The pixels a job asks for: its masked ones, or all of its rectangle.
std::size_t tracedPixels(const TileJob& job);

// What comes back for a tile: RGB8 of its masked pixels in scan order (or,
// for a batch of an irradiance field's probes, their values).
struct TileOutput {
  std::vector<std::uint8_t> rgb;
  std::vector<float> probes;  // IrradianceField::writeProbe's, probe after probe
  RayStats rays;
  double computeMs = 0.0;  // time spent tracing the tile, wherever it ran
};

class Renderer;

// Fills tiles of frames of one scene. The in-process service, the remote
// service (a glintd over the network) and the GL client all meet here.
class TileService {
 public:
  TileService() = default;
  virtual ~TileService() = default;
  // A service is a place where tiles are traced (a pool, a connection), not a value.
  TileService(const TileService&) = delete;
  TileService& operator=(const TileService&) = delete;
  // Renders every job of one frame. done(i, output) is called once per job,
  // never concurrently, in any order; returns when all are done. Throws
  // InputError when the frame cannot be rendered.
  virtual void render(const FrameSettings& frame, std::span<const TileJob> jobs,
                      const std::function<void(std::size_t, TileOutput&&)>& done) = 0;
  // Progress: `traced(n)` is told, never concurrently, that n of the current
  // render()'s pixels are traced (tracedPixels of its jobs; probes of a
  // field's batches), as they are: in process row by row, from servers tile
  // by tile. done() may come later: a distributed service holds outputs
  // until its frame is whole, so that the tiles of a server caught lying
  // meanwhile are traced again (n then falls). {} clears it.
  void onTraced(std::function<void(std::size_t)> traced) { traced_ = std::move(traced); }
  // Tiles traced at once (threads of the pool or of the server).
  virtual int parallelism() const = 0;
  // A frame's tiles may come in several render() calls (the hybrid frame
  // traces its sets apart): what a service reports and learns of a frame
  // covers every call from one beginFrame() to the next.
  virtual void beginFrame() {}

 protected:
  void traced(std::size_t count) const {
    if (traced_) traced_(count);
  }
  // Renders the jobs with one renderer on the pool, telling onTraced as
  // each is done.
  void renderOnPool(const Renderer& renderer, ThreadPool& pool, std::span<const TileJob> jobs,
                    const std::function<void(std::size_t, TileOutput&&)>& done) const;

 private:
  std::function<void(std::size_t)> traced_;
};

// Tiles rendered on this machine's thread pool; with an irradiance field
// (path transport), by the tracer that reads it (Renderer).
class LocalTileService : public TileService {
 public:
  LocalTileService(const PreparedScene& prepared, ThreadPool& pool, const IrradianceField* field = nullptr)
      : prepared_(prepared), pool_(pool), field_(field) {}
  void render(const FrameSettings& frame, std::span<const TileJob> jobs,
              const std::function<void(std::size_t, TileOutput&&)>& done) override;
  int parallelism() const override { return pool_.size(); }

 private:
  const PreparedScene& prepared_;
  ThreadPool& pool_;
  const IrradianceField* field_;
};

}  // namespace glint
