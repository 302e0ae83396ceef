#include "common/image/encoding.h"

#include <algorithm>
#include <cmath>

#include "common/math/power.h"

namespace glint {

Encoder::Encoder(const OutputSettings& output)
    : scale_(std::exp2(output.exposure)), srgb_(output.encoding == Encoding::kSrgb) {}

std::uint8_t Encoder::byte(float linear) const {
  const float v = std::clamp(linear * scale_, 0.0f, 1.0f);
  return toByte(srgb_ ? srgbEncode(v) : v);
}

float Encoder::displayed(float linear) const {
  const float v = std::clamp(linear * scale_, 0.0f, 1.0f);
  return srgb_ ? v : srgbDecode(v);
}

std::uint8_t toByte(float v) {
  const float c = std::clamp(v, 0.0f, 1.0f);  // NaN stays NaN; callers pass finite values
  return static_cast<std::uint8_t>(std::lround(c * 255.0f));
}

float srgbEncode(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * power(linear, 1.0f / 2.4f) - 0.055f;
}

float srgbDecode(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : power((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace glint
