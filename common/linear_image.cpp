#include "common/linear_image.h"

#include <algorithm>
#include <mutex>

namespace glint {

LinearImage renderLinear(const Renderer& renderer, ThreadPool& pool, RayStats& stats) {
  constexpr int kTileSize = 64;  // as glint render's tiles, so that the adaptive pattern's borders cost the same
  const FrameSettings& frame = renderer.frame();
  LinearImage image{frame.width, frame.height,
                    std::vector<float>(static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height) * 3)};
  const std::vector<TileRect> tiles = tileGrid(frame.width, frame.height, kTileSize);
  std::mutex statsMutex;
  pool.parallelFor(tiles.size(), [&](std::size_t t) {
    const TileRect& r = tiles[t];
    RayStats tileStats;
    std::vector<glm::vec3> linear;
    renderer.renderTileLinear(r, {}, linear, tileStats);
    std::size_t i = 0;
    for (int y = r.y; y < r.y + r.height; ++y) {
      for (int x = r.x; x < r.x + r.width; ++x, ++i) {
        float* p = &image.rgb[(static_cast<std::size_t>(y) * static_cast<std::size_t>(frame.width) +
                               static_cast<std::size_t>(x)) * 3];
        for (int k = 0; k < 3; ++k) p[k] = std::clamp(linear[i][k], 0.0f, 1.0f);
      }
    }
    std::lock_guard lock(statsMutex);
    stats += tileStats;
  });
  return image;
}

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
