#pragma once

#include <vector>

#include "common/frame.h"
#include "common/ray_stats.h"
#include "common/renderer.h"
#include "common/thread_pool.h"

namespace glint {

// A frame's linear colour before 8-bit rounding. Row 0 at the top, RGB floats.
struct LinearImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;
};

// kClamped: clamped to [0, 1] as the PNG would be (what accuracy is measured
// on); kUnbounded: as traced (what .exr and .pfm outputs hold).
enum class LinearRange { kClamped, kUnbounded };

// Every pixel of the renderer's frame (of options.window, if given), traced
// on the pool in tiles of options.tileSize; the rays are added to `stats`.
// The same values whatever the pool or the tiles.
LinearImage renderLinear(const Renderer& renderer, ThreadPool& pool, RayStats& stats, LinearRange range,
                         const FrameOptions& options = {});

// An 8-bit frame as linear values (byte / 255): the hybrid frame's raster
// pixels exist only as bytes.
LinearImage fromBytes(const FrameImage& image);

// The 8-bit frame a PNG holds: each value rounded as the tracer's tiles are.
FrameImage toBytes(const LinearImage& image);

// The per-channel mean of two images of one size (two half-sample
// references make one full one).
LinearImage average(const LinearImage& a, const LinearImage& b);

}  // namespace glint
