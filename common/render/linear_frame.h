#pragma once

#include "common/base/thread_pool.h"
#include "common/image/linear_image.h"
#include "common/render/frame.h"
#include "common/render/ray_stats.h"
#include "common/render/renderer.h"

namespace glint {

// kClamped: clamped to [0, 1] as the PNG would be (what accuracy is measured
// on); kUnbounded: as traced (what .exr and .pfm outputs hold).
enum class LinearRange { kClamped, kUnbounded };

// Every pixel of the renderer's frame (of options.window, if given), traced
// on the pool in tiles of options.tileSize; the rays are added to `stats`.
// The same values whatever the pool or the tiles.
LinearImage renderLinear(const Renderer& renderer, ThreadPool& pool, RayStats& stats, LinearRange range,
                         const FrameOptions& options = {});

}  // namespace glint
