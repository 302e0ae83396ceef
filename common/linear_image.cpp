#include "common/linear_image.h"

#include <algorithm>
#include <mutex>

namespace glint {

LinearImage renderLinear(const Renderer& renderer, ThreadPool& pool, RayStats& stats) {
  const FrameSettings& frame = renderer.frame();
  LinearImage image{frame.width, frame.height,
                    std::vector<float>(static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height) * 3)};
  std::mutex statsMutex;
  pool.parallelFor(static_cast<std::size_t>(frame.height), [&](std::size_t y) {
    RayStats rowStats;
    for (int x = 0; x < frame.width; ++x) {
      const glm::vec3 c = renderer.pixel(x, static_cast<int>(y), rowStats);
      float* p = &image.rgb[(y * static_cast<std::size_t>(frame.width) + static_cast<std::size_t>(x)) * 3];
      for (int k = 0; k < 3; ++k) p[k] = std::clamp(c[k], 0.0f, 1.0f);
    }
    std::lock_guard lock(statsMutex);
    stats += rowStats;
  });
  return image;
}

LinearImage fromBytes(const FrameImage& image) {
  LinearImage out{image.width, image.height, std::vector<float>(image.rgb.size())};
  std::transform(image.rgb.begin(), image.rgb.end(), out.rgb.begin(), [](std::uint8_t v) { return v / 255.0f; });
  return out;
}

LinearImage average(const LinearImage& a, const LinearImage& b) {
  LinearImage out = a;
  for (std::size_t i = 0; i < out.rgb.size(); ++i) out.rgb[i] = 0.5f * (a.rgb[i] + b.rgb[i]);
  return out;
}

}  // namespace glint
