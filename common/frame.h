#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "common/ray_stats.h"
#include "common/renderer.h"
#include "common/thread_pool.h"

namespace glint {

// An RGB8 image, row 0 at the top, 3 bytes per pixel.
struct FrameImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
};

struct FrameOptions {
  int tileSize = 32;
  // Called after each finished tile with (tiles done, tiles in all), from a
  // worker thread, never concurrently.
  std::function<void(int, int)> progress;
};

struct FrameResult {
  FrameImage image;
  RayStats stats;
};

// Renders every pixel through the tile interface, tiles spread over the pool.
// The image is the same whatever the pool size or tile size.
FrameResult renderFrame(const Renderer& renderer, ThreadPool& pool, const FrameOptions& options);

}  // namespace glint
