#include "common/render/linear_frame.h"

#include <algorithm>
#include <limits>
#include <mutex>

namespace glint {

LinearImage renderLinear(const Renderer& renderer, ThreadPool& pool, RayStats& stats, LinearRange range,
                         const FrameOptions& options) {
  const TileRect window = frameWindow(renderer.frame(), options);
  LinearImage image{window.width, window.height, std::vector<float>(window.pixelCount() * 3)};
  const std::vector<TileRect> tiles = tileGrid(window, std::max(1, options.tileSize));
  const float hi = range == LinearRange::kClamped ? 1.0f : std::numeric_limits<float>::max();
  const float lo = range == LinearRange::kClamped ? 0.0f : -hi;
  std::mutex statsMutex;
  std::size_t done = 0;  // pixels
  const Renderer::RowTraced rowTraced = [&](std::size_t n) {
    std::lock_guard lock(statsMutex);
    options.progress(static_cast<int>(done += n), static_cast<int>(window.pixelCount()));
  };
  pool.parallelFor(tiles.size(), [&](std::size_t t) {
    const TileRect& r = tiles[t];
    RayStats tileStats;
    std::vector<glm::vec3> linear;
    renderer.renderTileLinear(r, {}, linear, tileStats, options.progress ? rowTraced : Renderer::RowTraced{});
    std::size_t i = 0;
    for (int y = r.y; y < r.y + r.height; ++y) {
      for (int x = r.x; x < r.x + r.width; ++x, ++i) {
        float* p = &image.rgb[(static_cast<std::size_t>(y - window.y) * static_cast<std::size_t>(window.width) +
                               static_cast<std::size_t>(x - window.x)) * 3];
        for (int k = 0; k < 3; ++k) p[k] = std::clamp(linear[i][k], lo, hi);
      }
    }
    std::lock_guard lock(statsMutex);
    stats += tileStats;
  });
  return image;
}

}  // namespace glint
