#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace glint {

// GL's rows run bottom-up; Glint's images top-down.
inline void flipRows(std::vector<std::uint8_t>& pixels, int width, int height, int channels) {
  const auto row = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  for (int y = 0; y < height / 2; ++y) {
    const auto top = pixels.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * row);
    const auto bottom = pixels.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(height - 1 - y) * row);
    std::swap_ranges(top, top + static_cast<std::ptrdiff_t>(row), bottom);
  }
}

}  // namespace glint
