#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace glint {

// A rectangle of pixels; (x, y) is its top-left pixel, y grows downwards.
struct TileRect {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;

  std::size_t pixelCount() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
};

// A tile mask holds one bit per pixel of its rectangle in scan order (row by
// row from the top): pixel i is bit (i % 8) of byte i / 8, least significant
// bit first. Set bits are the pixels to trace. An empty mask means every pixel.
std::size_t maskByteCount(const TileRect& rect);
inline bool maskBit(std::span<const std::uint8_t> mask, std::size_t i) {
  return (mask[i / 8] >> (i % 8)) & 1u;
}
inline void setMaskBit(std::span<std::uint8_t> mask, std::size_t i) {
  mask[i / 8] = static_cast<std::uint8_t>(mask[i / 8] | (1u << (i % 8)));
}
std::size_t countMasked(const TileRect& rect, std::span<const std::uint8_t> mask);

// Cuts a window of a frame into tiles of at most tileSize x tileSize, row by
// row from the window's top-left.
std::vector<TileRect> tileGrid(const TileRect& window, int tileSize);
// The same for a whole width x height frame.
inline std::vector<TileRect> tileGrid(int width, int height, int tileSize) {
  return tileGrid(TileRect{0, 0, width, height}, tileSize);
}

}  // namespace glint
