#include "client/hybrid_frame.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <span>
#include <string>

#include "client/image_rows.h"
#include "common/error.h"
#include "common/timing.h"

namespace glint {
namespace {


// Pixels traced with one frame's settings: the masked objects' with the
// frame's own; the shadow edges' (pixels of surfaces OpenGL draws, traced
// only because the shadow maps could not decide) with direct light alone,
// as OpenGL draws their neighbours: the tracer's shadows, no reflected or
// refracted rays (max depth 1), the frame's samples.
struct TracedSet {
  gl::StencilMark mark;
  FrameSettings frame;
  std::vector<TileJob> jobs;  // the tiles holding pixels of `mark`, with those pixels' mask bits
  std::vector<TileOutput> outputs;
  std::size_t pixels = 0;
};

// Cuts the window into tiles once and gives each set the tiles that hold
// pixels of its mark; w is the frame's width.
void collectTiles(const std::vector<std::uint8_t>& mask, int w, const TileRect& window, int tileSize,
                  std::span<TracedSet> sets) {
  for (const TileRect& rect : tileGrid(window, std::max(1, tileSize))) {
    std::vector<TileJob> jobs(sets.size(), TileJob{rect, std::vector<std::uint8_t>(maskByteCount(rect), 0)});
    std::vector<std::size_t> counts(sets.size(), 0);
    for (int y = 0; y < rect.height; ++y) {
      for (int x = 0; x < rect.width; ++x) {
        const std::uint8_t mark =
            mask[static_cast<std::size_t>(rect.y + y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(rect.x + x)];
        for (std::size_t k = 0; k < sets.size(); ++k) {
          if (mark != sets[k].mark) continue;
          setMaskBit(jobs[k].mask, static_cast<std::size_t>(y * rect.width + x));
          ++counts[k];
        }
      }
    }
    for (std::size_t k = 0; k < sets.size(); ++k) {
      sets[k].pixels += counts[k];
      if (counts[k] > 0) sets[k].jobs.push_back(std::move(jobs[k]));
    }
  }
}

FrameSettings directLightOf(FrameSettings frame) {
  frame.tracing.maxDepth = 1;
  return frame;
}

// Draws one traced tile back (bottom-up rows for glDrawPixels); the stencil
// test keeps the pixels that are not its set's. `rect` is scratch space
// kept between tiles.
void drawTile(const gl::Api& gl, const TileJob& job, std::size_t index, const TileOutput& out, int frameHeight,
              std::vector<std::uint8_t>& rect) {
  const TileRect& r = job.rect;
  if (out.rgb.size() != countMasked(r, job.mask) * 3) {
    throw InputError("tile " + std::to_string(index) + ": the tile service returned " +
                     std::to_string(out.rgb.size()) + " bytes for " + std::to_string(countMasked(r, job.mask)) +
                     " masked pixels");
  }
  rect.assign(r.pixelCount() * 3, 0);
  std::size_t k = 0;
  for (int y = 0; y < r.height; ++y) {
    for (int x = 0; x < r.width; ++x) {
      const auto i = static_cast<std::size_t>(y * r.width + x);
      if (!maskBit(job.mask, i)) continue;
      const auto dst =
          (static_cast<std::size_t>(r.height - 1 - y) * static_cast<std::size_t>(r.width) + static_cast<std::size_t>(x)) *
          3;
      std::memcpy(&rect[dst], &out.rgb[k], 3);
      k += 3;
    }
  }
  gl.WindowPos2i(r.x, frameHeight - r.y - r.height);
  gl.DrawPixels(r.width, r.height, GL_RGB, GL_UNSIGNED_BYTE, rect.data());
}

// Sends a set's jobs to the service (in batches when the frame may be
// cancelled) and collects their outputs; false when cancelled.
bool traceTiles(TileService& service, TracedSet& set, const CancelCheck& cancelled, HybridResult& result) {
  const std::vector<TileJob>& jobs = set.jobs;
  std::vector<TileOutput>& outputs = set.outputs;
  constexpr std::size_t kTilesPerThread = 4;  // a batch: enough to keep every thread busy
  const std::size_t batch =
      cancelled ? kTilesPerThread * static_cast<std::size_t>(std::max(1, service.parallelism())) : jobs.size();
  outputs.assign(jobs.size(), {});
  double computeMs = 0.0;
  const Clock::time_point traceStart = Clock::now();
  for (std::size_t first = 0; first < jobs.size(); first += batch) {
    if (cancelled && cancelled()) return false;
    const std::span<const TileJob> part(jobs.data() + first, std::min(batch, jobs.size() - first));
    service.render(set.frame, part, [&](std::size_t i, TileOutput&& out) {
      result.rays += out.rays;
      computeMs += out.computeMs;
      outputs[first + i] = std::move(out);
    });
  }
  const double traceMs = msSince(traceStart);
  result.times.traceMs += traceMs;
  result.times.networkMs += std::max(0.0, traceMs - computeMs / std::max(1, service.parallelism()));
  return true;
}

}  // namespace

double medianOf(const std::vector<HybridTimes>& frames, double HybridTimes::*step) {
  std::vector<double> values;
  for (const HybridTimes& t : frames) values.push_back(t.*step);
  return median(std::move(values));
}

bool renderHybrid(const gl::Api& gl, gl::RasterScene& raster, TileService& service, const FrameSettings& frame,
                  const MaskSettings& mask, int tileSize, HybridResult& result, const std::optional<TileRect>& crop,
                  const CancelCheck& cancelled) {
  const Clock::time_point start = Clock::now();
  const int w = frame.width, h = frame.height;
  const TileRect whole{0, 0, w, h};
  const TileRect window = crop.value_or(whole);
  result.rays = RayStats{};
  result.times = HybridTimes{};

  // Several samples a pixel: the colour comes from the anti-aliased pass,
  // the first draws the marks (and depth) alone.
  const bool antialiased = mask.rule != MaskRule::kAll && raster.prepareAntialiased(frame);
  result.times.shadowMapMs = raster.draw(frame, mask, !antialiased);
  gl.Finish();
  result.times.rasterMs = msSince(start);

  const Clock::time_point readStart = Clock::now();
  if (mask.rule == MaskRule::kAll) {
    result.mask.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), gl::kMaskedPixel);
  } else {
    readPixels(gl, whole, h, GL_STENCIL_INDEX, 1, result.mask);
  }
  result.times.readbackMs = msSince(readStart);
  // The raster's colour, anti-aliased (the stencil mask stays the pixel
  // centre's); the pixels the tracer replaces are left unshaded.
  if (antialiased) {
    const Clock::time_point antialiasStart = Clock::now();
    raster.drawAntialiased(frame, result.mask);
    result.times.rasterMs += msSince(antialiasStart);
  }

  TracedSet sets[2] = {{gl::kMaskedPixel, frame, {}, {}, 0}, {gl::kShadowEdgePixel, directLightOf(frame), {}, {}, 0}};
  collectTiles(result.mask, w, window, tileSize, sets);
  result.shadowEdgePixels = sets[1].pixels;
  result.maskedPixels = sets[0].pixels + sets[1].pixels;
  result.tiles = static_cast<int>(sets[0].jobs.size() + sets[1].jobs.size());
  for (TracedSet& set : sets) {
    if (!traceTiles(service, set, cancelled, result)) return false;
  }

  const Clock::time_point composeStart = Clock::now();
  gl.Disable(GL_DEPTH_TEST);
  if (mask.rule == MaskRule::kAll) {
    gl.Disable(GL_STENCIL_TEST);
  } else {
    gl.Enable(GL_STENCIL_TEST);
    gl.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  }
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  std::vector<std::uint8_t> scratch;
  for (const TracedSet& set : sets) {
    gl.StencilFunc(GL_EQUAL, set.mark, 0xff);  // a tile's rectangle draws only its set's pixels
    for (std::size_t j = 0; j < set.jobs.size(); ++j) drawTile(gl, set.jobs[j], j, set.outputs[j], h, scratch);
  }
  result.image.width = window.width;
  result.image.height = window.height;
  readPixels(gl, window, h, GL_RGB, 3, result.image.rgb);
  gl.Disable(GL_STENCIL_TEST);
  result.times.composeMs = msSince(composeStart);
  result.times.totalMs = msSince(start);
  return true;
}

}  // namespace glint
