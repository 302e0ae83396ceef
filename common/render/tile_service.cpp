#include "common/render/tile_service.h"

#include <mutex>

#include "common/render/renderer.h"
#include "common/base/timing.h"

namespace glint {

void LocalTileService::render(const FrameSettings& frame, std::span<const TileJob> jobs,
                              const std::function<void(std::size_t, TileOutput&&)>& done) {
  const Renderer renderer(prepared_, frame, EffectPlan::derive(prepared_.scene(), frame), field_);
  renderOnPool(renderer, pool_, jobs, done);
}

std::size_t tracedPixels(const TileJob& job) {
  return job.mask.empty() ? job.rect.pixelCount() : countMasked(job.rect, job.mask);
}

void TileService::renderOnPool(const Renderer& renderer, ThreadPool& pool, std::span<const TileJob> jobs,
                               const std::function<void(std::size_t, TileOutput&&)>& done) const {
  std::mutex doneMutex;
  std::size_t pixels = 0;
  const Renderer::RowTraced rowTraced = [&](std::size_t n) {
    std::lock_guard lock(doneMutex);
    traced(pixels += n);
  };
  pool.parallelFor(jobs.size(), [&](std::size_t i) {
    TileOutput out;
    out.rgb.reserve(jobs[i].rect.pixelCount() * 3);
    const auto start = Clock::now();
    renderer.renderTile(jobs[i].rect, jobs[i].mask, out.rgb, out.rays, traced_ ? rowTraced : Renderer::RowTraced{});
    out.computeMs = msSince(start);
    std::lock_guard lock(doneMutex);
    done(i, std::move(out));
  });
}

}  // namespace glint
