#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "client/raster/gl_api.h"
#include "client/raster/raster_scene.h"
#include "common/render/frame.h"
#include "common/render/tile_service.h"

namespace glint {

// Milliseconds spent in each step of a hybrid frame.
struct HybridTimes {
  double rasterMs = 0.0;     // OpenGL draws the scene and marks each pixel
  double shadowMapMs = 0.0;  // of rasterMs, drawing the shadow maps (the first frame that needs them)
  double readbackMs = 0.0;   // glReadPixels of the marks, depth and colour, and the edges found
  double traceMs = 0.0;      // the tile service fills the traced pixels
  double networkMs = 0.0;    // of traceMs, not spent tracing: traceMs - compute / parallelism
  double composeMs = 0.0;    // the traced pixels laid over OpenGL's
  double totalMs = 0.0;
};

// The median of one step's time over frames.
double medianOf(const std::vector<HybridTimes>& frames, double HybridTimes::*step);

struct HybridResult {
  FrameImage image;                  // the frame, or the crop window of it
  std::vector<std::uint8_t> mask;    // one PixelMark per pixel, row 0 at the top: 0 OpenGL, else traced
  std::size_t maskedPixels = 0;      // traced pixels, all sets together
  std::size_t shadowEdgePixels = 0;  // traced because the shadow maps could not decide
  std::size_t rasterEdgePixels = 0;  // traced because they straddle an edge of what OpenGL draws
  std::size_t outOfFocusPixels = 0;  // traced because the lens blurs them (or a blur may reach them)
  int tiles = 0;                     // tiles sent to the tile service (each traced set apart)
  RayStats rays;
  HybridTimes times;
  // Scratch kept between frames: the raster's surface, depth and colour.
  std::vector<std::uint32_t> surface;
  std::vector<float> depth;
  std::vector<std::uint8_t> colour;
};

// Asked between batches of tiles: true abandons the frame (the camera has
// moved on).
using CancelCheck = std::function<bool()>;

// What the caller of a hybrid frame may ask of it: `cancelled` (see
// renderHybrid), and `progress`, told (pixels traced, pixels to trace) as
// the frame's traced pixels come in, never concurrently.
struct HybridControl {
  CancelCheck cancelled;
  std::function<void(int, int)> progress;
};

// The raster half of a hybrid frame of the whole image, alone: OpenGL draws
// and marks the pixels the tracer would fill; result's mask, pixel counts,
// tile count and raster and readback times are a renderHybrid's, and nothing
// is traced (glint info).
void markHybrid(const gl::Api& gl, gl::RasterScene& raster, const FrameSettings& frame, const MaskSettings& mask,
                int tileSize, HybridResult& result);

// The thesis's frame: OpenGL rasterizes the scene at one sample a pixel and
// marks the pixels the tracer fills (masked objects, undecided shadows, and
// the edges of what it draws, its anti-aliasing: client/raster/raster_edges.h);
// the marks, depth and colour are read back, tiles with traced pixels go to
// the tile service (the masked pixels with the frame's settings, the others
// with direct light), and the traced pixels are laid over OpenGL's. Under
// the mask rule "all" every pixel is traced. The frame is written into
// `result`: passing the same object frame after frame keeps its image-sized
// buffers (fresh megabyte buffers per frame cost more in page faults than
// the reads themselves). With `crop`, only that window's pixels are traced
// and the image is the window (the mask stays the whole frame's). With
// `control.cancelled`, the tiles go to the service in batches of a few per
// thread it traces with, and the frame is abandoned when cancelled() says so
// between two: renderHybrid returns false, result.image still holds the previous
// frame and the rest of result is the abandoned frame's.
bool renderHybrid(const gl::Api& gl, gl::RasterScene& raster, TileService& service, const FrameSettings& frame,
                  const MaskSettings& mask, int tileSize, HybridResult& result,
                  const std::optional<TileRect>& crop = std::nullopt, const HybridControl& control = {});

}  // namespace glint
