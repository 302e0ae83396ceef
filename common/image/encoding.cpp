#include "common/image/encoding.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "common/math/power.h"

namespace glint {

Encoder::Encoder(const OutputSettings& output)
    : scale_(twoToThe(output.exposure)), srgb_(output.encoding == Encoding::kSrgb) {}

std::uint8_t Encoder::byte(float linear) const {
  const float v = std::clamp(linear * scale_, 0.0f, 1.0f);
  return toByte(srgb_ ? srgbEncode(v) : v);
}

float Encoder::displayed(float linear) const { return displayedByte(byte(linear)); }

float Encoder::decoded(std::uint8_t byte) const {
  const float v = static_cast<float>(byte) / 255.0f;
  return (srgb_ ? srgbDecode(v) : v) / scale_;
}

LinearImage displayedLight(const LinearImage& image, const Encoder& encoder) {
  LinearImage light = image;
  for (float& v : light.rgb) v = encoder.displayed(v);
  return light;
}

LinearImage displayedLight(const FrameImage& image) {
  LinearImage light{image.width, image.height, std::vector<float>(image.rgb.size())};
  for (std::size_t i = 0; i < image.rgb.size(); ++i) light.rgb[i] = displayedByte(image.rgb[i]);
  return light;
}

LinearImage decodeBytes(const FrameImage& image, const Encoder& encoder) {
  LinearImage linear{image.width, image.height, std::vector<float>(image.rgb.size())};
  for (std::size_t i = 0; i < image.rgb.size(); ++i) linear.rgb[i] = encoder.decoded(image.rgb[i]);
  return linear;
}

FrameImage encodeBytes(const LinearImage& image, const Encoder& encoder) {
  FrameImage bytes{image.width, image.height, std::vector<std::uint8_t>(image.rgb.size())};
  for (std::size_t i = 0; i < image.rgb.size(); ++i) bytes.rgb[i] = encoder.byte(image.rgb[i]);
  return bytes;
}

LinearImage scaledLight(const FrameImage& image, const Encoder& encoder) {
  LinearImage light = decodeBytes(image, encoder);
  for (float& v : light.rgb) v *= encoder.scale();
  return light;
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

float displayedByte(std::uint8_t byte) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int v = 0; v < 256; ++v) t[static_cast<std::size_t>(v)] = srgbDecode(static_cast<float>(v) / 255.0f);
    return t;
  }();
  return table[byte];
}

}  // namespace glint
