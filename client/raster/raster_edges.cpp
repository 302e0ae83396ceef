#include "client/raster/raster_edges.h"

#include <cmath>
#include <stdexcept>

#include "client/raster/pixel_mark.h"

namespace glint {
namespace {

struct Pixels {
  std::span<const std::uint32_t> surface;
  std::span<const float> depth;
  std::uint32_t object(std::size_t i) const { return surface[i] >> kPixelMarkBits; }
  std::uint8_t mark(std::size_t i) const { return markOf(surface[i]); }
};

// Whether p's depth, extrapolated through p from `before` (p's other
// neighbour on the line, or none), misses q's by more than the tolerance.
bool misses(const Pixels& px, std::size_t before, bool hasBefore, std::size_t p, std::size_t q) {
  const float dp = px.depth[p];
  const bool line = hasBefore && px.object(before) == px.object(p);
  const float expected = line ? 2.0f * dp - px.depth[before] : dp;
  return std::fabs(px.depth[q] - expected) > kEdgeDepthTolerance * dp;
}

// Whether p and its next neighbour q on a line of `count` pixels (step
// apart, p at index `at` of the line) straddle an edge.
bool straddle(const Pixels& px, std::size_t p, std::size_t q, std::size_t step, int at, int count) {
  if (px.object(p) != px.object(q)) return true;
  if (px.object(p) == 0) return false;  // background on both sides
  return misses(px, p - step, at > 0, p, q) && misses(px, q + step, at + 2 < count, q, p);
}

// Marks p as an edge seen from q (whose raster mark is `across`).
void markEdge(std::uint8_t own, std::uint8_t across, std::uint8_t& mark) {
  if (own != kRasterPixel) return;  // traced already
  if (across == kMaskedPixel) {
    mark = kMaskedPixel;
  } else if (mark != kMaskedPixel) {
    mark = kRasterEdgePixel;
  }
}

}  // namespace

std::size_t markRasterEdges(std::span<const std::uint32_t> surface, std::span<const float> depth, int width,
                            int height, std::span<std::uint8_t> marks) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (surface.size() != n || depth.size() != n || marks.size() != n) {
    throw std::invalid_argument("markRasterEdges: one surface, depth and mark a pixel");
  }
  const Pixels px{surface, depth};
  for (std::size_t i = 0; i < n; ++i) marks[i] = px.mark(i);
  const auto visit = [&](std::size_t p, std::size_t q, std::size_t step, int at, int count) {
    if (!straddle(px, p, q, step, at, count)) return;
    markEdge(px.mark(p), px.mark(q), marks[p]);
    markEdge(px.mark(q), px.mark(p), marks[q]);
  };
  const auto w = static_cast<std::size_t>(width);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x);
      if (x + 1 < width) visit(p, p + 1, 1, x, width);
      if (y + 1 < height) visit(p, p + w, w, y, height);
    }
  }
  std::size_t edges = 0;
  for (std::size_t i = 0; i < n; ++i) edges += marks[i] != px.mark(i) ? 1 : 0;
  return edges;
}

}  // namespace glint
