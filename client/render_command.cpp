#include "client/render_command.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "client/progress.h"
#include "client/remote_tile_service.h"
#include "client/stats_json.h"
#include "common/error.h"
#include "common/frame.h"
#include "common/image_io.h"
#include "common/sampling.h"
#include "common/scene_load.h"
#include "proto/scene_bundle.h"

namespace glint {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void writeStats(const std::string& path, const nlohmann::json& record) {
  if (path == "-") {
    std::cout << record.dump() << '\n' << std::flush;
    return;
  }
  std::ofstream out(path, std::ios::trunc);
  out << record.dump() << '\n';
  if (!out) throw InputError("--stats " + path + ": cannot write the file");
}

}  // namespace

void applyOverrides(const RenderOptions& o, Scene& scene) {
  if (o.width) scene.width = *o.width;
  if (o.height) scene.height = *o.height;
  if (o.pattern) scene.sampling.pattern = *o.pattern;
  if (o.samples) scene.sampling.samples = *o.samples;
  if (o.filter) scene.sampling.filter = *o.filter;
  if (o.seed) scene.sampling.seed = *o.seed;
  if (o.maxDepth) scene.tracing.maxDepth = *o.maxDepth;
  if (o.minWeight) scene.tracing.minWeight = *o.minWeight;
  if (!validSampleCount(scene.sampling.pattern, scene.sampling.samples)) {
    throw InputError("--samples " + std::to_string(scene.sampling.samples) +
                     ": the regular pattern takes 1, 2 or a square number (4, 9, 16, ...); "
                     "use --pattern jittered for other counts");
  }
  const std::string rule = o.mask == "scene" ? (scene.mask.rule == MaskRule::kAll    ? "all"
                                                : scene.mask.rule == MaskRule::kNone ? "none"
                                                                                     : "auto")
                                             : o.mask;
  if (rule != "all") {
    throw InputError("--mask " + rule +
                     ": the hybrid OpenGL path is not built yet; use --mask all for a full ray trace");
  }
}

void runRender(const RenderOptions& options) {
  const Clock::time_point start = Clock::now();
  FrameTimes times;
  proto::LoadedBundle loaded = proto::loadSceneBundle(options.scene);
  applyOverrides(options, loaded.scene);
  const FrameSettings frame = loaded.scene.frame();
  const EffectPlan plan = EffectPlan::derive(loaded.scene, frame);
  const std::size_t dropped = loaded.scene.geometry.droppedTriangles();
  times.loadMs = msSince(start);

  // In process (the default) or through a glintd: the same tiles either way.
  const Clock::time_point prepareStart = Clock::now();
  std::optional<PreparedScene> prepared;
  std::optional<ThreadPool> pool;
  std::unique_ptr<TileService> service;
  if (options.server.empty()) {
    BvhSettings bvhSettings;
    bvhSettings.builder = options.bvh;
    prepared.emplace(std::move(loaded.scene), bvhSettings);
    pool.emplace(resolveThreadCount(options.threads));
    service = std::make_unique<LocalTileService>(*prepared, *pool);
  } else {
    service = std::make_unique<RemoteTileService>(options.server, loaded.bundle);
  }
  times.bvhMs = msSince(prepareStart);

  FrameOptions frameOptions;
  frameOptions.tileSize = options.tileSize;
  FrameResult result;
  const Clock::time_point traceStart = Clock::now();
  {
    ProgressBar progress("rendering");
    frameOptions.progress = [&progress](int done, int total) { progress.update(done, total); };
    result = renderFrame(*service, frame, frameOptions);
  }
  times.traceMs = msSince(traceStart);
  writePng(options.output, result.image);
  times.totalMs = msSince(start);

  const std::size_t pixels = static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height);
  if (!options.statsPath.empty()) {
    writeStats(options.statsPath, frameStats(0, frame.width, frame.height, pixels, result.stats, times, plan, dropped));
  }
  if (!options.quiet) {
    const std::string where = options.server.empty() ? std::to_string(pool->size()) + " threads"
                                                     : "server " + options.server;
    std::fprintf(stderr, "%s: %dx%d, %d spp, %s: trace %.1f ms, total %.1f ms, %.2f M rays -> %s\n",
                 options.scene.c_str(), frame.width, frame.height, frame.sampling.samples, where.c_str(),
                 times.traceMs, times.totalMs, static_cast<double>(result.stats.total()) / 1e6,
                 options.output.c_str());
    if (result.stats.nonFiniteSamples > 0) {
      std::fprintf(stderr, "warning: %llu samples were not finite and were discarded\n",
                   static_cast<unsigned long long>(result.stats.nonFiniteSamples));
    }
  }
}

}  // namespace glint
