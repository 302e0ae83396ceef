#pragma once

#include <vector>

#include "common/frame.h"
#include "common/ray_stats.h"
#include "common/renderer.h"
#include "common/thread_pool.h"

namespace glint {

// A frame's linear colour before 8-bit rounding, clamped to [0, 1] as the
// PNG would be: what accuracy is measured on. Row 0 at the top, RGB floats.
struct LinearImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;
};

// Every pixel of the renderer's frame, traced on the pool (rows in
// parallel); the rays are added to `stats`. The same values whatever the pool.
LinearImage renderLinear(const Renderer& renderer, ThreadPool& pool, RayStats& stats);

// An 8-bit frame as linear values (byte / 255): the hybrid frame's raster
// pixels exist only as bytes.
LinearImage fromBytes(const FrameImage& image);

// The 8-bit frame a PNG holds: each value rounded as the tracer's tiles are.
FrameImage toBytes(const LinearImage& image);

// The per-channel mean of two images of one size (two half-sample
// references make one full one).
LinearImage average(const LinearImage& a, const LinearImage& b);

}  // namespace glint
