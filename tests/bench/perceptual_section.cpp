#include "tests/bench/perceptual_section.h"

#include <cstdio>
#include <filesystem>

#include "client/raster/hybrid_frame.h"
#include "client/raster/offscreen_context.h"
#include "client/raster/raster_scene.h"
#include "common/base/timing.h"
#include "common/image/encoding.h"
#include "common/metrics/flip.h"
#include "common/render/linear_frame.h"
#include "common/render/renderer.h"
#include "common/render/tile_service.h"
#include "common/scene/scene_load.h"

namespace glint::bench {
namespace {

// A converged full trace: 256 jittered samples (16 when quick), depth 16, no cut-off.
LinearImage reference(const PreparedScene& prepared, FrameSettings frame, ThreadPool& pool, bool quick) {
  frame.sampling.pattern = SamplePattern::kJittered;
  frame.sampling.samples = quick ? 16 : 256;
  frame.tracing.maxDepth = 16;
  frame.tracing.minWeight = 0.0f;
  RayStats ignored;
  return renderLinear(Renderer(prepared, frame), pool, ignored, LinearRange::kClamped);
}

struct RuleRow {
  std::vector<double> frameMs;
  HybridResult last;
};

}  // namespace

void perceptualSection(const std::string& scenes, bool quick) {
  const int frames = quick ? 1 : 9;
  std::printf("\n## The mask rules auto and perceptual (median of %d frames, 2 tracing threads)\n\n", frames);
  std::printf("FLIP: mean against the converged full trace (%d jittered samples, depth 16), as displayed; the "
              "perceptual rule's threshold is the scene's (default 0.3). Frames alternate between the rules.\n\n",
              quick ? 16 : 256);
  std::printf("| scene | rule | frame ms | traced pixels | rays | primary rays | FLIP | **rays / auto** | "
              "**FLIP / auto** | frame / auto |\n|---|---|---|---|---|---|---|---|---|---|\n");
  for (const char* name : {"room.json", "glass.json", "bunny.json", "room-bright.json"}) {
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
    MaskSettings rules[2] = {scene.mask, scene.mask};
    rules[0].rule = MaskRule::kAuto;
    rules[1].rule = MaskRule::kPerceptual;
    RuleRow rows[2];
    for (int f = 0; f < frames + 1; ++f) {  // the first frame compiles the shaders
      for (int r = 0; r < 2; ++r) {
        renderHybrid(context.api(), raster, service, frame, rules[r], 64, rows[r].last);
        if (f > 0) rows[r].frameMs.push_back(rows[r].last.times.totalMs);
      }
    }
    const Encoder encoder(frame.output);
    const LinearImage converged = displayedLight(reference(prepared, frame, pool, quick), encoder);
    double flips[2], times[2];
    for (int r = 0; r < 2; ++r) {
      flips[r] = flipStats(flip(converged, displayedLight(rows[r].last.image))).mean;
      times[r] = median(rows[r].frameMs);
    }
    for (int r = 0; r < 2; ++r) {
      const HybridResult& h = rows[r].last;
      const double rays = static_cast<double>(h.rays.total()), autoRays = static_cast<double>(rows[0].last.rays.total());
      std::printf("| %s | %s | %.1f | %zu | %llu | %llu | %.5f | **%.2f** | **%.3f** | %.2f |\n", name,
                  r == 0 ? "auto" : "perceptual", times[r], h.maskedPixels,
                  static_cast<unsigned long long>(h.rays.total()), static_cast<unsigned long long>(h.rays.primary),
                  flips[r], rays / autoRays, flips[r] / flips[0], times[r] / times[0]);
    }
  }
}

}  // namespace glint::bench
