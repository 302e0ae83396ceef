#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "client/raster/gl_api.h"
#include "common/render/tile.h"

namespace glint {

// GL's rows run bottom-up; Glint's images top-down.
template <typename T>
void flipRows(std::vector<T>& pixels, int width, int height, int channels) {
  const auto row = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  for (int y = 0; y < height / 2; ++y) {
    const auto top = pixels.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * row);
    const auto bottom = pixels.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(height - 1 - y) * row);
    std::swap_ranges(top, top + static_cast<std::ptrdiff_t>(row), bottom);
  }
}

// Reads a window of the bound read buffer (y from the top) into `pixels`
// (resized, so that its buffer is kept from one frame to the next) with rows
// top-down; `type` is GL's name for T.
template <typename T>
void readPixels(const gl::Api& gl, const TileRect& window, int frameHeight, GLenum format, GLenum type, int channels,
                std::vector<T>& pixels) {
  pixels.resize(window.pixelCount() * static_cast<std::size_t>(channels));
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadPixels(window.x, frameHeight - window.y - window.height, window.width, window.height, format, type,
                pixels.data());
  flipRows(pixels, window.width, window.height, channels);
}

}  // namespace glint
