#include "client/colour_edges.h"

#include <array>
#include <stdexcept>
#include <vector>

#include "client/pixel_mark.h"
#include "common/image/encoding.h"
#include "common/image/flip.h"

namespace glint {
namespace {

// Each 8-bit value's displayed light.
const std::array<float, 256>& displayTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int v = 0; v < 256; ++v) t[static_cast<std::size_t>(v)] = srgbDecode(static_cast<float>(v) / 255.0f);
    return t;
  }();
  return table;
}

}  // namespace

std::size_t markColourEdges(std::span<const std::uint8_t> rgb, int width, int height, float threshold,
                            std::span<std::uint8_t> marks) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (rgb.size() != 3 * n || marks.size() != n) {
    throw std::invalid_argument("markColourEdges: one colour and one mark a pixel");
  }
  const std::array<float, 256>& light = displayTable();
  std::vector<glm::vec3> lab(n);
  for (std::size_t i = 0; i < n; ++i) {
    lab[i] = flipLab({light[rgb[3 * i]], light[rgb[3 * i + 1]], light[rgb[3 * i + 2]]});
  }
  const std::vector<std::uint8_t> own(marks.begin(), marks.end());
  std::size_t marked = 0;
  const auto visit = [&](std::size_t p, std::size_t q) {
    if (own[p] == kMaskedPixel || own[q] == kMaskedPixel) return;
    if (flipColourError(lab[p], lab[q]) <= threshold) return;
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
