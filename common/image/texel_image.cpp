#include "common/image/texel_image.h"

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

// byte / 255 for every byte, computed once.
struct UnitTable {
  float value[256];
  constexpr UnitTable() : value() {
    for (int i = 0; i < 256; ++i) value[i] = static_cast<float>(i) / 255.0f;
  }
};
constexpr UnitTable kUnit;

}  // namespace

std::uint8_t linearTexelByte(float linear) {
  const float v = std::isfinite(linear) ? std::clamp(linear, 0.0f, 1.0f) : 0.0f;
  return static_cast<std::uint8_t>(std::lround(v * 255.0f));
}

glm::vec3 Image::texel(std::size_t index) const {
  const std::uint8_t* t = &rgb[3 * index];
  return {kUnit.value[t[0]], kUnit.value[t[1]], kUnit.value[t[2]]};
}

}  // namespace glint
