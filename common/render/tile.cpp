#include "common/render/tile.h"

#include <algorithm>

namespace glint {

std::size_t maskByteCount(const TileRect& rect) { return (rect.pixelCount() + 7) / 8; }

std::size_t countMasked(const TileRect& rect, std::span<const std::uint8_t> mask) {
  if (mask.empty()) return rect.pixelCount();
  std::size_t n = 0;
  for (std::size_t i = 0; i < rect.pixelCount(); ++i) n += maskBit(mask, i) ? 1 : 0;
  return n;
}

std::vector<TileRect> tileGrid(const TileRect& window, int tileSize) {
  std::vector<TileRect> tiles;
  const int x1 = window.x + window.width, y1 = window.y + window.height;
  for (int y = window.y; y < y1; y += tileSize) {
    for (int x = window.x; x < x1; x += tileSize) {
      tiles.push_back({x, y, std::min(tileSize, x1 - x), std::min(tileSize, y1 - y)});
    }
  }
  return tiles;
}

}  // namespace glint
