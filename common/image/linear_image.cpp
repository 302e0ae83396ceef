#include "common/image/linear_image.h"

#include <algorithm>

#include "common/image/encoding.h"

namespace glint {

LinearImage fromBytes(const FrameImage& image) {
  LinearImage out{image.width, image.height, std::vector<float>(image.rgb.size())};
  std::transform(image.rgb.begin(), image.rgb.end(), out.rgb.begin(), [](std::uint8_t v) { return v / 255.0f; });
  return out;
}

FrameImage toBytes(const LinearImage& image) {
  FrameImage out{image.width, image.height, std::vector<std::uint8_t>(image.rgb.size())};
  std::transform(image.rgb.begin(), image.rgb.end(), out.rgb.begin(), toByte);
  return out;
}

LinearImage average(const LinearImage& a, const LinearImage& b) {
  LinearImage out = a;
  for (std::size_t i = 0; i < out.rgb.size(); ++i) out.rgb[i] = 0.5f * (a.rgb[i] + b.rgb[i]);
  return out;
}

}  // namespace glint
