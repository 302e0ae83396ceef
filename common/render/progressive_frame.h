#pragma once

#include <functional>
#include <vector>

#include "common/base/thread_pool.h"
#include "common/render/ray_stats.h"
#include "common/render/renderer.h"
#include "common/render/tile.h"
#include "common/image/frame_image.h"

namespace glint {

// A frame whose samples come in passes (glint view's, while its camera
// rests): each pass adds the next samples of every pixel to the sums so far,
// in the order Renderer::pixel() adds them, so that after the last pass the
// frame is the one-pass render's at the frame's samples, byte for byte. The
// passes double what is in: 1, 2, 4, ... samples a pixel, then the rest.
// For the regular, jittered and sobol patterns (the adaptive ones decide
// per pixel from its neighbours' samples).
class ProgressiveFrame {
 public:
  ProgressiveFrame(const Renderer& renderer, int tileSize);

  // Samples every pixel holds so far.
  int samples() const { return samples_; }
  bool complete() const;
  // Adds the next pass, its tiles traced on the pool. `cancelled` is asked
  // between batches of tiles; when it says true the pass stops and returns
  // false, leaving the frame half-summed: it may then only be dropped.
  bool addPass(ThreadPool& pool, const std::function<bool()>& cancelled = {});
  // The samples so far as 8-bit RGB, encoded as the frame's output says.
  FrameImage image() const;
  // The rays of every pass so far.
  const RayStats& stats() const { return stats_; }

 private:
  void addToTile(const TileRect& tile, int first, int end, RayStats& stats);

  const Renderer& renderer_;
  std::vector<TileRect> tiles_;
  std::vector<Renderer::PixelSamples> pixels_;  // the frame's, in scan order
  int samples_ = 0;
  RayStats stats_;
};

}  // namespace glint
