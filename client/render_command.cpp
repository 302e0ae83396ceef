#include "client/render_command.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "client/hybrid_frame.h"
#include "client/offscreen_context.h"
#include "client/progress.h"
#include "client/raster_scene.h"
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

// The mask as the thesis's figures show it: white where the tracer fills.
void writeMaskPng(const std::string& path, const std::vector<std::uint8_t>& mask, int width, int height) {
  FrameImage image{width, height, std::vector<std::uint8_t>(mask.size() * 3)};
  for (std::size_t i = 0; i < mask.size(); ++i) image.rgb[3 * i] = image.rgb[3 * i + 1] = image.rgb[3 * i + 2] = mask[i] ? 255 : 0;
  writePng(path, image);
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
  if (o.mask == "all") scene.mask.rule = MaskRule::kAll;
  if (o.mask == "auto") scene.mask.rule = MaskRule::kAuto;
  if (o.mask == "none") scene.mask.rule = MaskRule::kNone;
  if (o.maskThreshold) scene.mask.minReflectivity = *o.maskThreshold;
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

  // --mask all is the full ray trace: every pixel through the tile service.
  // Other rules draw the frame with OpenGL and trace only the masked pixels.
  const Scene& scene = prepared ? prepared->scene() : loaded.scene;
  FrameResult result;
  std::size_t masked = static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height);
  std::optional<HybridTimes> hybridTimes;
  int tiles = 0;
  const Clock::time_point traceStart = Clock::now();
  if (scene.mask.rule == MaskRule::kAll && options.maskOut.empty()) {
    FrameOptions frameOptions;
    frameOptions.tileSize = options.tileSize;
    ProgressBar progress("rendering");
    frameOptions.progress = [&progress](int done, int total) { progress.update(done, total); };
    result = renderFrame(*service, frame, frameOptions);
    tiles = static_cast<int>(tileGrid(frame.width, frame.height, options.tileSize).size());
  } else {
    gl::OffscreenContext context(frame.width, frame.height);
    gl::RasterScene raster(context.api(), scene);
    HybridResult hybrid = renderHybrid(context.api(), raster, *service, frame, scene.mask, options.tileSize);
    result.image = std::move(hybrid.image);
    result.stats = hybrid.rays;
    masked = hybrid.maskedPixels;
    tiles = hybrid.tiles;
    hybridTimes = hybrid.times;
    if (!options.maskOut.empty()) writeMaskPng(options.maskOut, hybrid.mask, frame.width, frame.height);
  }
  times.traceMs = hybridTimes ? hybridTimes->traceMs : msSince(traceStart);
  writePng(options.output, result.image);
  times.totalMs = msSince(start);

  if (!options.statsPath.empty()) {
    nlohmann::json record = frameStats(0, frame.width, frame.height, masked, result.stats, times, plan, dropped);
    record["tiles"] = tiles;
    if (hybridTimes) {
      record["raster_ms"] = hybridTimes->rasterMs;
      record["readback_ms"] = hybridTimes->readbackMs;
      record["compose_ms"] = hybridTimes->composeMs;
    }
    writeStats(options.statsPath, record);
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
