#include "common/render/frame.h"

#include <algorithm>
#include <cstring>

#include "common/base/error.h"

namespace glint {

TileRect frameWindow(const FrameSettings& frame, const FrameOptions& options) {
  return options.window.value_or(TileRect{0, 0, frame.width, frame.height});
}

FrameResult renderFrame(TileService& service, const FrameSettings& frame, const FrameOptions& options) {
  const TileRect window = frameWindow(frame, options);
  FrameResult result;
  result.image.width = window.width;
  result.image.height = window.height;
  result.image.rgb.assign(window.pixelCount() * 3, 0);
  std::vector<TileJob> jobs;
  for (const TileRect& rect : tileGrid(window, std::max(1, options.tileSize))) {
    jobs.push_back({rect, {}});
  }
  service.beginFrame();
  struct Progress {  // told as tiles are traced, for as long as this frame renders
    TileService& service;
    ~Progress() { service.onTraced({}); }
  } progress{service};
  if (options.progress) {
    const auto pixels = static_cast<int>(window.pixelCount());
    service.onTraced([&, pixels](std::size_t n) { options.progress(static_cast<int>(n), pixels); });
  }
  service.render(frame, jobs, [&](std::size_t i, TileOutput&& out) {
    const TileRect& rect = jobs[i].rect;
    if (out.rgb.size() != rect.pixelCount() * 3) {
      throw InputError("tile " + std::to_string(i) + ": " + std::to_string(out.rgb.size()) +
                       " bytes of colour for " + std::to_string(rect.pixelCount()) + " pixels");
    }
    for (int row = 0; row < rect.height; ++row) {
      const std::size_t dst = (static_cast<std::size_t>(rect.y - window.y + row) * static_cast<std::size_t>(window.width) +
                               static_cast<std::size_t>(rect.x - window.x)) * 3;
      std::memcpy(&result.image.rgb[dst], &out.rgb[static_cast<std::size_t>(row * rect.width) * 3],
                  static_cast<std::size_t>(rect.width) * 3);
    }
    result.stats += out.rays;
  });
  return result;
}

FrameResult renderFrame(const Renderer& renderer, ThreadPool& pool, const FrameOptions& options) {
  // A service that renders with this renderer (its frame and effect plan).
  struct RendererService : TileService {
    const Renderer& renderer;
    ThreadPool& pool;
    RendererService(const Renderer& r, ThreadPool& p) : renderer(r), pool(p) {}
    void render(const FrameSettings&, std::span<const TileJob> jobs,
                const std::function<void(std::size_t, TileOutput&&)>& done) override {
      renderOnPool(renderer, pool, jobs, done);
    }
    int parallelism() const override { return pool.size(); }
  } service(renderer, pool);
  return renderFrame(service, renderer.frame(), options);
}

}  // namespace glint
