#include "tests/bench/soft_shadow_section.h"

#include <cstdio>
#include <filesystem>

#include "client/raster/hybrid_frame.h"
#include "client/raster/offscreen_context.h"
#include "client/raster/raster_scene.h"
#include "common/base/timing.h"
#include "common/image/encoding.h"
#include "common/metrics/flip.h"
#include "common/render/frame.h"
#include "common/render/linear_frame.h"
#include "common/render/renderer.h"
#include "common/render/tile_service.h"
#include "common/scene/scene_load.h"

namespace glint::bench {
namespace {

// 1,024 points of the light a pixel: 16 jittered samples of 64 (quick: 4 of
// 16), with another seed.
LinearImage reference(const PreparedScene& prepared, FrameSettings frame, ThreadPool& pool, bool quick) {
  frame.sampling.pattern = SamplePattern::kJittered;
  frame.sampling.samples = quick ? 4 : 16;
  frame.sampling.lightSamples = quick ? 16 : 64;
  frame.sampling.seed += 1;  // points of its own, not the frames'
  RayStats ignored;
  return renderLinear(Renderer(prepared, frame), pool, ignored, LinearRange::kClamped);
}

struct Row {
  std::vector<double> ms;
  FrameImage image;
  RayStats rays;
};

// One scene's table.
void softShadowTable(const std::string& scenes, const char* name, bool quick) {
  const int frames = quick ? 1 : 9;
  const Scene scene = loadSceneFile(std::filesystem::path(scenes) / name);
  FrameSettings frame = scene.frame;
  if (quick) {
    frame.width = 160;
    frame.height = 120;
  }
  const PreparedScene prepared(scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService service(prepared, pool);
  gl::OffscreenContext context(frame.width, frame.height);
  gl::RasterScene raster(context.api(), prepared.scene());
  const Encoder encoder(frame.output);
  const LinearImage converged = displayedLight(reference(prepared, frame, pool, quick), encoder);
  std::printf("\n## Soft shadows: the hybrid frame and the full trace (%s, %dx%d, median of %d frames, "
              "2 tracing threads)\n\n",
              name, frame.width, frame.height, frames);
  std::printf("FLIP: mean against a full trace of %d light samples a pixel, as displayed. The scene's 4 jittered "
              "samples a pixel.\n\n",
              quick ? 64 : 1024);
  std::printf("| light samples | full: shadow rays | ms | FLIP | hybrid: shadow rays | traced pixels | ms | FLIP | "
              "**shadow rays / full** | **FLIP / full** | frame / full |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int lightSamples : {4, 16, 64}) {
    frame.sampling.lightSamples = lightSamples;
    Row full, hybrid;
    HybridResult result;
    for (int f = 0; f < frames + 1; ++f) {  // the first hybrid frame compiles the shaders
      const Clock::time_point start = Clock::now();
      FrameResult traced = renderFrame(service, frame, {});
      if (f > 0) full.ms.push_back(msSince(start));
      full.image = std::move(traced.image);
      full.rays = traced.stats;
      renderHybrid(context.api(), raster, service, frame, scene.mask, 64, result);
      if (f > 0) hybrid.ms.push_back(result.times.totalMs);
    }
    const double flipFull = flipStats(flip(converged, displayedLight(full.image))).mean;
    const double flipHybrid = flipStats(flip(converged, displayedLight(result.image))).mean;
    const double fullMs = median(full.ms), hybridMs = median(hybrid.ms);
    std::printf("| %d | %llu | %.1f | %.5f | %llu | %zu | %.1f | %.5f | **%.2f** | **%.3f** | %.2f |\n", lightSamples,
                static_cast<unsigned long long>(full.rays.shadow), fullMs, flipFull,
                static_cast<unsigned long long>(result.rays.shadow), result.maskedPixels, hybridMs, flipHybrid,
                static_cast<double>(result.rays.shadow) / static_cast<double>(full.rays.shadow), flipHybrid / flipFull,
                hybridMs / fullMs);
  }
}

}  // namespace

void softShadowSection(const std::string& scenes, bool quick) {
  for (const char* name : {"soft-shadows.json", "sphere-light.json"}) softShadowTable(scenes, name, quick);
}

}  // namespace glint::bench
