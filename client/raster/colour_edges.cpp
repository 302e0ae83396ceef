#include "client/raster/colour_edges.h"

#include <stdexcept>
#include <vector>

#include "client/raster/pixel_mark.h"
#include "common/image/encoding.h"
#include "common/image/flip_colour.h"

namespace glint {
std::size_t markColourEdges(std::span<const std::uint8_t> rgb, int width, int height, float threshold,
                            std::span<std::uint8_t> marks) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (rgb.size() != 3 * n || marks.size() != n) {
    throw std::invalid_argument("markColourEdges: one colour and one mark a pixel");
  }
  std::vector<glm::vec3> lab(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* c = &rgb[3 * i];
    const bool asBefore = i > 0 && c[0] == c[-3] && c[1] == c[-2] && c[2] == c[-1];  // runs of one colour are common
    lab[i] = asBefore ? lab[i - 1] : flipLab({displayedByte(c[0]), displayedByte(c[1]), displayedByte(c[2])});
  }
  const VisibleDifference visible(threshold);
  std::size_t marked = 0;
  const auto visit = [&](std::size_t p, std::size_t q) {
    // Only raster marks become edges, so a masked mark here is the raster's own.
    if (marks[p] == kMaskedPixel || marks[q] == kMaskedPixel) return;
    if (!visible(lab[p], lab[q])) return;
    for (const std::size_t i : {p, q}) {
      if (marks[i] != kRasterPixel) continue;
      marks[i] = kRasterEdgePixel;
      ++marked;
    }
  };
  const auto w = static_cast<std::size_t>(width);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x);
      if (x + 1 < width) visit(p, p + 1);
      if (y + 1 < height) visit(p, p + w);
    }
  }
  return marked;
}

}  // namespace glint
