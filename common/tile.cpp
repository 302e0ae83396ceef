#include "common/tile.h"

#include <algorithm>

namespace glint {

std::size_t maskByteCount(const TileRect& rect) { return (rect.pixelCount() + 7) / 8; }

std::size_t countMasked(const TileRect& rect, std::span<const std::uint8_t> mask) {
  if (mask.empty()) return rect.pixelCount();
  std::size_t n = 0;
  for (std::size_t i = 0; i < rect.pixelCount(); ++i) n += maskBit(mask, i) ? 1 : 0;
  return n;
}

std::vector<TileRect> tileGrid(int width, int height, int tileSize) {
  std::vector<TileRect> tiles;
  for (int y = 0; y < height; y += tileSize) {
    for (int x = 0; x < width; x += tileSize) {
      tiles.push_back({x, y, std::min(tileSize, width - x), std::min(tileSize, height - y)});
    }
  }
  return tiles;
}

}  // namespace glint
