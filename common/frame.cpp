#include "common/frame.h"

#include <algorithm>
#include <cstring>
#include <mutex>

namespace glint {

FrameResult renderFrame(const Renderer& renderer, ThreadPool& pool, const FrameOptions& options) {
  const int width = renderer.frame().width;
  const int height = renderer.frame().height;
  FrameResult result;
  result.image.width = width;
  result.image.height = height;
  result.image.rgb.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3, 0);
  const std::vector<TileRect> tiles = tileGrid(width, height, std::max(1, options.tileSize));
  std::vector<RayStats> tileStats(tiles.size());
  std::mutex progressMutex;
  int done = 0;
  pool.parallelFor(tiles.size(), [&](std::size_t t) {
    const TileRect& rect = tiles[t];
    std::vector<std::uint8_t> rgb;
    rgb.reserve(rect.pixelCount() * 3);
    renderer.renderTile(rect, {}, rgb, tileStats[t]);
    for (int row = 0; row < rect.height; ++row) {
      const std::size_t dst =
          (static_cast<std::size_t>(rect.y + row) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(rect.x)) * 3;
      std::memcpy(&result.image.rgb[dst], &rgb[static_cast<std::size_t>(row * rect.width) * 3],
                  static_cast<std::size_t>(rect.width) * 3);
    }
    if (options.progress) {
      std::lock_guard lock(progressMutex);
      options.progress(++done, static_cast<int>(tiles.size()));
    }
  });
  for (const RayStats& s : tileStats) result.stats += s;
  return result;
}

}  // namespace glint
