#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace glint {

// Decoded texture image: 8-bit RGB texels as the file held them (3 bytes a
// texel, a quarter of floats), row 0 at the top. A texel reads as byte / 255.
struct Image {
  static constexpr std::size_t kBytesPerTexel = 3;

  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // width * height * 3

  glm::vec3 texel(std::size_t index) const;
};

// An image's linear values as floats, row 0 at the top.
struct FloatPixels {
  static constexpr std::size_t kBytesPerTexel = 3 * sizeof(float);

  int width = 0;
  int height = 0;
  std::vector<float> rgb;  // width * height * 3
};

// A linear value (an HDR or EXR image's) as a texel byte: clamped to [0, 1]
// and rounded to the nearest of 255 steps; a value that is not finite is 0.
std::uint8_t linearTexelByte(float linear);

}  // namespace glint
