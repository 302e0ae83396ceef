#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "common/image/frame_image.h"
#include "common/render/ray_stats.h"
#include "common/render/renderer.h"
#include "common/base/thread_pool.h"
#include "common/render/tile_service.h"

namespace glint {

struct FrameOptions {
  int tileSize = 64;
  // The pixels rendered (--crop); none: the whole frame. The image is the
  // window's size.
  std::optional<TileRect> window;
  // Called as pixels are traced with (pixels traced, pixels in all), never
  // concurrently (TileService::onTraced: the count falls when a lying
  // server's tiles are to be traced again).
  std::function<void(int, int)> progress;
};

// The window the options ask for, or the whole frame.
TileRect frameWindow(const FrameSettings& frame, const FrameOptions& options);

struct FrameResult {
  FrameImage image;
  RayStats stats;
};

// Renders every pixel of a frame through a tile service and composes the
// tiles. The image is the same whatever the service, pool size or tile size.
FrameResult renderFrame(TileService& service, const FrameSettings& frame, const FrameOptions& options);

// The same, in process: the renderer's scene and frame on the pool.
FrameResult renderFrame(const Renderer& renderer, ThreadPool& pool, const FrameOptions& options);

}  // namespace glint
