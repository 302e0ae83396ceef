#include "client/raster/focus_blur.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "client/raster/pixel_mark.h"
#include "common/scene/camera.h"

namespace glint {
namespace {

// Within `radius` along one axis of a flag: out[i] is set when a flag is set
// among the `count` cells at i - radius .. i + radius (cells `step` apart).
void spread(const std::vector<std::uint8_t>& in, std::vector<std::uint8_t>& out, std::size_t first, std::size_t step,
            int count, int radius) {
  int inWindow = 0;
  for (int i = -radius; i < count; ++i) {
    const int enter = i + radius, leave = i - radius - 1;
    if (enter < count) inWindow += in[first + static_cast<std::size_t>(enter) * step];
    if (leave >= 0) inWindow -= in[first + static_cast<std::size_t>(leave) * step];
    if (i >= 0) out[first + static_cast<std::size_t>(i) * step] = inWindow > 0 ? 1 : 0;
  }
}

}  // namespace

std::size_t markOutOfFocus(const FrameSettings& frame, float near, const std::vector<float>& depth,
                           std::vector<std::uint8_t>& mask) {
  const Camera camera(frame.camera, frame.width, frame.height);
  std::vector<std::uint8_t> blurred(depth.size(), 0);
  float widest = 0.0f;
  for (std::size_t i = 0; i < depth.size(); ++i) {
    const float distance = depth[i] > 0.0f ? near / depth[i] : std::numeric_limits<float>::max();
    const float circle = camera.circleOfConfusion(distance);
    if (circle <= 0.5f) continue;
    blurred[i] = 1;
    widest = std::max(widest, circle);
  }
  if (widest == 0.0f) return 0;
  const int radius = static_cast<int>(std::ceil(0.5f * std::min(widest, 2.0f * static_cast<float>(frame.width + frame.height))));
  const auto w = static_cast<std::size_t>(frame.width);
  std::vector<std::uint8_t> rows(depth.size(), 0);
  for (int y = 0; y < frame.height; ++y) spread(blurred, rows, static_cast<std::size_t>(y) * w, 1, frame.width, radius);
  for (int x = 0; x < frame.width; ++x) spread(rows, blurred, static_cast<std::size_t>(x), w, frame.height, radius);
  std::size_t marked = 0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (!blurred[i] || mask[i] == kMaskedPixel) continue;
    mask[i] = kMaskedPixel;
    ++marked;
  }
  return marked;
}

}  // namespace glint
