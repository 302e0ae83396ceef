#include "tests/bench/gl_backend_section.h"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "client/raster/hybrid_frame.h"
#include "client/raster/offscreen_context.h"
#include "client/raster/raster_scene.h"
#include "common/base/timing.h"
#include "tests/bench/bench_timing.h"
#include "common/scene/scene_load.h"

namespace glint::bench {
namespace {

// One backend on one scene: its start-up, its GL pass per frame, and the
// last frame's marks and colour.
struct BackendRun {
  double startMs = 0.0;
  std::vector<double> passMs;
  HybridResult last;
};

BackendRun runBackend(gl::GlBackend kind, const Scene& scene, const FrameSettings& frame, int frames) {
  BackendRun run;
  std::optional<gl::OffscreenContext> context;
  std::optional<gl::RasterScene> raster;
  run.startMs = medianMs(1, [&] {
    context.emplace(frame.width, frame.height, kind);
    raster.emplace(context->api(), scene);
  });
  for (int f = 0; f < frames + 1; ++f) {
    markHybrid(context->api(), *raster, frame, scene.mask, 64, run.last);
    if (f > 0) run.passMs.push_back(run.last.times.totalMs);  // the first compiles the shaders
  }
  return run;
}

}  // namespace

void glBackendSection(const std::string& scenes, bool quick) {
  const int frames = quick ? 2 : 21;
  std::printf("\n## Headless OpenGL: EGL (surfaceless) and OSMesa, median of %d frames\n\n", frames);
  std::printf(
      "GL pass = the hybrid frame's raster and readback (markHybrid); start = context made and scene "
      "uploaded; both on Mesa's llvmpipe.\n\n| scene | backend | start ms | **GL pass ms** | marks and colour "
      "equal the first backend's |\n|---|---|---:|---:|---|\n");
  for (const char* name : {"room.json", "room-gl-floor.json", "glass.json", "bunny.json"}) {
    const Scene scene = loadSceneFile(std::filesystem::path(scenes) / name);
    FrameSettings frame = scene.frame;
    if (quick) {
      frame.width = 160;
      frame.height = 120;
    }
    std::optional<BackendRun> first;
    for (const gl::GlBackend kind : gl::builtGlBackends()) {
      BackendRun run = runBackend(kind, scene, frame, frames);
      const bool same = !first || (run.last.mask == first->last.mask && run.last.colour == first->last.colour);
      std::printf("| %s | %s | %.1f | **%.2f** | %s |\n", name, std::string(enumWord(kind)).c_str(), run.startMs,
                  median(run.passMs), first ? (same ? "yes" : "**no**") : "(the first)");
      if (!first) first = std::move(run);
    }
  }
}

}  // namespace glint::bench
