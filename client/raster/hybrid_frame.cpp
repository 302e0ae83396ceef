#include "client/raster/hybrid_frame.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "client/raster/colour_edges.h"
#include "client/raster/focus_blur.h"
#include "client/raster/pixel_mark.h"
#include "client/raster/raster_edges.h"
#include "common/base/compute_pool.h"
#include "common/base/error.h"
#include "common/base/timing.h"

namespace glint {
namespace {

// Pixels traced with one frame's settings: the masked objects' with the
// frame's own; the others (pixels of surfaces OpenGL draws, traced because
// the shadow maps could not decide or because they straddle an edge) with
// direct light alone, as OpenGL draws their neighbours: the tracer's
// shadows, no reflected or refracted rays (max depth 1), the frame's samples.
struct TracedSet {
  bool directLight;  // the set's pixels: those with tracedWithDirectLight(mark), else the masked ones
  FrameSettings frame;
  std::vector<TileJob> jobs;  // the tiles holding pixels of the set, with those pixels' mask bits
  std::vector<TileOutput> outputs;
  std::size_t pixels = 0;

  bool takes(std::uint8_t mark) const { return mark != kRasterPixel && tracedWithDirectLight(mark) == directLight; }
};

// Cuts the window into tiles once and gives each set the tiles that hold
// pixels of its marks; w is the frame's width.
void collectTiles(const std::vector<std::uint8_t>& mask, int w, const TileRect& window, int tileSize,
                  std::span<TracedSet> sets) {
  for (const TileRect& rect : tileGrid(window, std::max(1, tileSize))) {
    std::vector<TileJob> jobs(sets.size(), TileJob{rect, std::vector<std::uint8_t>(maskByteCount(rect), 0)});
    std::vector<std::size_t> counts(sets.size(), 0);
    for (int y = 0; y < rect.height; ++y) {
      for (int x = 0; x < rect.width; ++x) {
        const std::uint8_t mark = mask[static_cast<std::size_t>(rect.y + y) * static_cast<std::size_t>(w) +
                                       static_cast<std::size_t>(rect.x + x)];
        for (std::size_t k = 0; k < sets.size(); ++k) {
          if (!sets[k].takes(mark)) continue;
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

// The window's pixels traced for a shadow's edge, and those the raster's
// edges marked (their mark is not the raster's own).
void countEdges(const TileRect& window, int w, HybridResult& result) {
  result.shadowEdgePixels = result.rasterEdgePixels = 0;
  for (int y = window.y; y < window.y + window.height; ++y) {
    for (int x = window.x; x < window.x + window.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      result.shadowEdgePixels += result.mask[i] == kShadowEdgePixel ? 1 : 0;
      // The raster's edges change a mark to 3 or 1; the penumbra's to 2; a
      // lens's blur to 1 (where it reaches an edge, the pixel counts as out
      // of focus).
      const std::uint8_t mark = result.mask[i];
      const bool blurred = result.outOfFocusPixels > 0 && mark == kMaskedPixel;
      result.rasterEdgePixels +=
          !result.surface.empty() && mark != markOf(result.surface[i]) && mark != kShadowEdgePixel && !blurred ? 1 : 0;
    }
  }
}

// The settings a traced set's tiles go with: under the perceptual rule, the
// perceptual pattern (a ray at each pixel's centre, the frame's samples
// where a neighbour's differs visibly); a set of direct light stops at depth 1.
FrameSettings tracedFrame(FrameSettings frame, const MaskSettings& mask, bool directLight) {
  if (mask.rule == MaskRule::kPerceptual) frame.sampling.pattern = SamplePattern::kPerceptual;
  if (directLight) frame.tracing.maxDepth = 1;
  return frame;
}

// A frame's two traced sets, empty: the masked pixels, then direct light.
std::array<TracedSet, 2> tracedSets(const FrameSettings& frame, const MaskSettings& mask) {
  return {TracedSet{false, tracedFrame(frame, mask, false), {}, {}, 0},
          TracedSet{true, tracedFrame(frame, mask, true), {}, {}, 0}};
}

// Lays one traced tile's pixels over the window's image (rows from the top).
void composeTile(const TileJob& job, std::size_t index, const TileOutput& out, const TileRect& window,
                 std::vector<std::uint8_t>& rgb) {
  const TileRect& r = job.rect;
  if (out.rgb.size() != countMasked(r, job.mask) * 3) {
    throw InputError("tile " + std::to_string(index) + ": the tile service returned " + std::to_string(out.rgb.size()) +
                     " bytes for " + std::to_string(countMasked(r, job.mask)) + " masked pixels");
  }
  std::size_t k = 0;
  for (int y = 0; y < r.height; ++y) {
    for (int x = 0; x < r.width; ++x) {
      if (!maskBit(job.mask, static_cast<std::size_t>(y * r.width + x))) continue;
      const auto dst = (static_cast<std::size_t>(r.y - window.y + y) * static_cast<std::size_t>(window.width) +
                        static_cast<std::size_t>(r.x - window.x + x)) *
                       3;
      std::memcpy(&rgb[dst], &out.rgb[k], 3);
      k += 3;
    }
  }
}

// Sends a set's jobs to the service (in batches when the frame may be
// cancelled) and collects their outputs; false when cancelled. `before`
// pixels of `total` were traced in the sets before it.
bool traceTiles(TileService& service, TracedSet& set, const HybridControl& control, int before, int total,
                HybridResult& result) {
  const CancelCheck& cancelled = control.cancelled;
  const std::vector<TileJob>& jobs = set.jobs;
  std::vector<TileOutput>& outputs = set.outputs;
  constexpr std::size_t kTilesPerThread = 4;  // a batch: enough to keep every thread busy
  const std::size_t batch =
      cancelled ? kTilesPerThread * static_cast<std::size_t>(std::max(1, service.parallelism())) : jobs.size();
  struct Progress {  // told for as long as this set is traced
    TileService& service;
    ~Progress() { service.onTraced({}); }
  } progress{service};
  outputs.assign(jobs.size(), {});
  double computeMs = 0.0;
  const Clock::time_point traceStart = Clock::now();
  for (std::size_t first = 0; first < jobs.size(); first += batch) {
    if (cancelled && cancelled()) return false;
    const std::span<const TileJob> part(jobs.data() + first, std::min(batch, jobs.size() - first));
    if (control.progress) {
      service.onTraced([&, before](std::size_t n) { control.progress(before + static_cast<int>(n), total); });
    }
    for (const TileJob& job : part) before += static_cast<int>(tracedPixels(job));
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

// The window's rows of a whole frame's RGB, moved to its front.
void cropRows(std::vector<std::uint8_t>& rgb, int frameWidth, const TileRect& window) {
  const auto row = static_cast<std::size_t>(window.width) * 3;
  for (int y = 0; y < window.height; ++y) {
    const auto from = (static_cast<std::size_t>(window.y + y) * static_cast<std::size_t>(frameWidth) +
                       static_cast<std::size_t>(window.x)) *
                      3;
    std::memmove(&rgb[static_cast<std::size_t>(y) * row], &rgb[from], row);
  }
  rgb.resize(row * static_cast<std::size_t>(window.height));
}

// Marks for tracing (with direct light, as an undecided shadow) each pixel
// OpenGL shades whose point is not proved to see every area light whole:
// the penumbra and umbra (client/raster/penumbra_proof.h). A block of pixels
// is proved at once where it can be (one region query for all its points);
// in one that cannot be, each pixel whose ray to a light's middle is blocked
// is marked at once (most of the umbra), and the block is cut in four, down
// to kSmallestBlock pixels a side, whose pixels are proved one by one
// against the primitives that may block that block (one region query). The
// blocks' rows are shared out on the compute pool.
constexpr int kProofBlock = 8;
constexpr int kSmallestBlock = 4;

// The smallest block's pixels, each proved alone against the primitives that
// may block the block.
void markPenumbraPixels(const gl::PenumbraProof& proof, const glm::vec3& eye, std::span<const std::size_t> pixels,
                        std::span<const glm::vec3> at, std::vector<std::uint8_t>& mask) {
  const std::optional<std::vector<std::uint32_t>> suspects = proof.suspects(at, eye);
  if (suspects && suspects->empty()) return;
  for (std::size_t k = 0; k < at.size(); ++k) {
    if (mask[pixels[k]] != kRasterPixel) continue;
    if (suspects ? !proof.seesWhole(at[k], eye, *suspects) : !proof.seesWhole(at[k], eye)) {
      mask[pixels[k]] = kShadowEdgePixel;
    }
  }
}

void markPenumbraBlock(const gl::RasterScene& raster, const gl::RasterScene::PixelPoints& points,
                       const FrameSettings& frame, int x0, int y0, int size, HybridResult& result) {
  std::vector<std::size_t> pixels;
  std::vector<glm::vec3> at;
  for (int y = y0; y < std::min(frame.height, y0 + size); ++y) {
    for (int x = x0; x < std::min(frame.width, x0 + size); ++x) {
      const std::size_t i =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(frame.width) + static_cast<std::size_t>(x);
      if (result.mask[i] != kRasterPixel || !raster.objectLit(result.surface[i] >> kPixelMarkBits)) continue;
      pixels.push_back(i);
      at.push_back(points.at(x, y, result.depth[i]));
    }
  }
  if (at.empty()) return;
  if (size == kSmallestBlock) return markPenumbraPixels(raster.penumbra(), frame.camera.eye, pixels, at, result.mask);
  if (at.size() > 1 && raster.penumbra().allSeeWhole(at, frame.camera.eye)) return;
  if (size == kProofBlock) {
    for (std::size_t k = 0; k < at.size(); ++k) {
      if (raster.penumbra().plainlyBlocked(at[k], frame.camera.eye)) result.mask[pixels[k]] = kShadowEdgePixel;
    }
  }
  const int half = size / 2;
  for (int q = 0; q < 4; ++q) {
    markPenumbraBlock(raster, points, frame, x0 + (q & 1) * half, y0 + (q >> 1) * half, half, result);
  }
}

void markPenumbra(const gl::RasterScene& raster, const FrameSettings& frame, HybridResult& result) {
  const gl::RasterScene::PixelPoints points = raster.pixelPoints(frame);
  const int blocksX = (frame.width + kProofBlock - 1) / kProofBlock;
  const int blocksY = (frame.height + kProofBlock - 1) / kProofBlock;
  computePool().parallelFor(static_cast<std::size_t>(blocksY), [&](std::size_t by) {
    const int y0 = static_cast<int>(by) * kProofBlock;
    for (int bx = 0; bx < blocksX; ++bx) {
      markPenumbraBlock(raster, points, frame, bx * kProofBlock, y0, kProofBlock, result);
    }
  });
}

// Reads the raster back: each pixel's mark into result.mask, and the
// window's colour into result.colour. The edges of what OpenGL draws are
// traced under the rules auto and perceptual when the frame takes several
// samples a pixel (one sample at the centre would give the raster's own
// value); under perceptual, its visible colour edges too (read from the
// whole frame, so that a crop decides as the frame does).
void readRaster(const gl::RasterScene& raster, const FrameSettings& frame, const MaskSettings& mask,
                const TileRect& window, HybridResult& result) {
  raster.target().readSurface(result.surface);
  result.mask.resize(result.surface.size());
  const bool edges = mask.rule == MaskRule::kAuto || mask.rule == MaskRule::kPerceptual;
  const bool penumbra = edges && raster.penumbra().active();
  const bool lens = edges && frame.camera.aperture > 0.0f;
  if ((edges && frame.sampling.samples > 1) || penumbra || lens) raster.target().readDepth(result.depth);
  if (edges && frame.sampling.samples > 1) {
    markRasterEdges(result.surface, result.depth, frame.width, frame.height, result.mask);
  } else {
    std::transform(result.surface.begin(), result.surface.end(), result.mask.begin(), markOf);
  }
  if (penumbra) markPenumbra(raster, frame, result);
  result.outOfFocusPixels = lens ? markOutOfFocus(frame, raster.nearPlane(frame), result.depth, result.mask) : 0;
  if (mask.rule != MaskRule::kPerceptual || frame.sampling.samples == 1) {
    raster.target().readColour(window, result.colour);
    return;
  }
  raster.target().readColour(TileRect{0, 0, frame.width, frame.height}, result.colour);
  markColourEdges(result.colour, frame.width, frame.height, frame.sampling.perceptualThreshold, result.mask);
  cropRows(result.colour, frame.width, window);
}

// Under the rule "all" OpenGL draws nothing: every pixel is traced.
void traceEverything(const FrameSettings& frame, const TileRect& window, HybridResult& result) {
  result.surface.clear();
  result.mask.assign(static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height), kMaskedPixel);
  result.colour.assign(window.pixelCount() * 3, 0);
}

// The raster half: OpenGL draws and marks (or, under "all", every pixel is
// marked), the marks are read back and the sets given their tiles.
void markFrame(const gl::Api& gl, gl::RasterScene& raster, const FrameSettings& frame, const MaskSettings& mask,
               const TileRect& window, int tileSize, std::span<TracedSet> sets, HybridResult& result) {
  const Clock::time_point start = Clock::now();
  result.rays = RayStats{};
  result.times = HybridTimes{};
  if (mask.rule == MaskRule::kAll) {
    traceEverything(frame, window, result);
  } else {
    result.times.shadowMapMs = raster.draw(frame, mask);
    gl.Finish();
    result.times.rasterMs = msSince(start);
    const Clock::time_point readStart = Clock::now();
    readRaster(raster, frame, mask, window, result);
    result.times.readbackMs = msSince(readStart);
  }
  collectTiles(result.mask, frame.width, window, tileSize, sets);
  countEdges(window, frame.width, result);
  result.maskedPixels = 0;
  result.tiles = 0;
  for (const TracedSet& set : sets) {
    result.maskedPixels += set.pixels;
    result.tiles += static_cast<int>(set.jobs.size());
  }
}

}  // namespace

void markHybrid(const gl::Api& gl, gl::RasterScene& raster, const FrameSettings& frame, const MaskSettings& mask,
                int tileSize, HybridResult& result) {
  std::array<TracedSet, 2> sets = tracedSets(frame, mask);
  markFrame(gl, raster, frame, mask, TileRect{0, 0, frame.width, frame.height}, tileSize, sets, result);
  result.times.totalMs = result.times.rasterMs + result.times.readbackMs;
}

double medianOf(const std::vector<HybridTimes>& frames, double HybridTimes::*step) {
  std::vector<double> values;
  for (const HybridTimes& t : frames) values.push_back(t.*step);
  return median(std::move(values));
}

bool renderHybrid(const gl::Api& gl, gl::RasterScene& raster, TileService& service, const FrameSettings& frame,
                  const MaskSettings& mask, int tileSize, HybridResult& result, const std::optional<TileRect>& crop,
                  const HybridControl& control) {
  const Clock::time_point start = Clock::now();
  const TileRect window = crop.value_or(TileRect{0, 0, frame.width, frame.height});
  std::array<TracedSet, 2> sets = tracedSets(frame, mask);
  markFrame(gl, raster, frame, mask, window, tileSize, sets, result);
  service.beginFrame();
  const int pixels = static_cast<int>(sets[0].pixels + sets[1].pixels);
  int before = 0;
  for (TracedSet& set : sets) {
    if (!traceTiles(service, set, control, before, pixels, result)) return false;
    before += static_cast<int>(set.pixels);
  }

  const Clock::time_point composeStart = Clock::now();
  for (const TracedSet& set : sets) {
    for (std::size_t j = 0; j < set.jobs.size(); ++j)
      composeTile(set.jobs[j], j, set.outputs[j], window, result.colour);
  }
  result.image.width = window.width;
  result.image.height = window.height;
  result.image.rgb.swap(result.colour);
  result.times.composeMs = msSince(composeStart);
  result.times.totalMs = msSince(start);
  return true;
}

}  // namespace glint
