#include "common/render/progressive_frame.h"

#include <algorithm>
#include <mutex>
#include <stdexcept>

#include "common/image/encoding.h"

namespace glint {

ProgressiveFrame::ProgressiveFrame(const Renderer& renderer, int tileSize)
    : renderer_(renderer),
      tiles_(tileGrid(renderer.frame().width, renderer.frame().height, std::max(1, tileSize))),
      pixels_(static_cast<std::size_t>(renderer.frame().width) * static_cast<std::size_t>(renderer.frame().height)) {
  const SamplePattern pattern = renderer.frame().sampling.pattern;
  if (pattern == SamplePattern::kAdaptive || pattern == SamplePattern::kPerceptual) {
    throw std::logic_error("ProgressiveFrame: the adaptive patterns cannot be summed in passes");
  }
}

bool ProgressiveFrame::complete() const { return samples_ >= renderer_.frame().sampling.samples; }

void ProgressiveFrame::addToTile(const TileRect& tile, int first, int end, RayStats& stats) {
  const auto width = static_cast<std::size_t>(renderer_.frame().width);
  for (int y = tile.y; y < tile.y + tile.height; ++y) {
    for (int x = tile.x; x < tile.x + tile.width; ++x) {
      Renderer::PixelSamples& p = pixels_[static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x)];
      renderer_.addSamples(x, y, first, end, p, stats);
    }
  }
}

bool ProgressiveFrame::addPass(ThreadPool& pool, const std::function<bool()>& cancelled) {
  if (complete()) return true;
  const int first = samples_;
  const int end = std::min(renderer_.frame().sampling.samples, std::max(1, 2 * samples_));
  constexpr std::size_t kTilesPerThread = 4;  // a batch: enough to keep every thread busy
  const std::size_t batch = kTilesPerThread * static_cast<std::size_t>(std::max(1, pool.size()));
  std::mutex statsMutex;
  for (std::size_t from = 0; from < tiles_.size(); from += batch) {
    if (cancelled && cancelled()) return false;
    pool.parallelFor(std::min(batch, tiles_.size() - from), [&](std::size_t i) {
      RayStats tileStats;
      addToTile(tiles_[from + i], first, end, tileStats);
      std::lock_guard lock(statsMutex);
      stats_ += tileStats;
    });
  }
  samples_ = end;
  return true;
}

FrameImage ProgressiveFrame::image() const {
  const Encoder encoder(renderer_.frame().output);
  FrameImage image{renderer_.frame().width, renderer_.frame().height, {}};
  image.rgb.reserve(pixels_.size() * 3);
  for (const Renderer::PixelSamples& p : pixels_) {
    const glm::vec3 c = renderer_.resolve(p);
    image.rgb.insert(image.rgb.end(), {encoder.byte(c.r), encoder.byte(c.g), encoder.byte(c.b)});
  }
  return image;
}

}  // namespace glint
