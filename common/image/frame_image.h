#pragma once

#include <cstdint>
#include <vector>

namespace glint {

// An RGB8 image, row 0 at the top, 3 bytes per pixel.
struct FrameImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
};

}  // namespace glint
