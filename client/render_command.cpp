#include "client/render_command.h"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <cstdio>
#include <algorithm>
#include <memory>
#include <optional>

#include "client/hybrid_frame.h"
#include "client/offscreen_context.h"
#include "client/progress.h"
#include "client/provenance.h"
#include "client/distributed_tile_service.h"
#include "client/raster_scene.h"
#include "client/stats_json.h"
#include "client/tile_backend.h"
#include "common/error.h"
#include "common/frame.h"
#include "common/image_io.h"
#include "common/frame_limits.h"
#include "common/load_limits.h"
#include "common/scene_load.h"
#include "common/timing.h"
#include "proto/scene_bundle.h"

namespace glint {
namespace {

// The mask as the thesis's figures show it: white where the tracer fills.
void writeMaskPng(const std::string& path, const std::vector<std::uint8_t>& mask, int width, int height) {
  FrameImage image{width, height, std::vector<std::uint8_t>(mask.size() * 3)};
  for (std::size_t i = 0; i < mask.size(); ++i) image.rgb[3 * i] = image.rgb[3 * i + 1] = image.rgb[3 * i + 2] = mask[i] ? 255 : 0;
  writePng(path, image);
}

// Medians over the frames, as the thesis's Table 4.1: the RT unit's time
// beside the whole frame, and each step of the hybrid frame.
void printTimingTable(const std::vector<HybridTimes>& frames, bool hybrid) {
  const auto median = [&frames](double HybridTimes::*step) { return medianOf(frames, step); };
  std::fprintf(stderr, "median of %zu frames:\n", frames.size());
  if (hybrid) {
    std::fprintf(stderr, "  raster     %8.1f ms\n  readback   %8.1f ms\n", median(&HybridTimes::rasterMs),
                 median(&HybridTimes::readbackMs));
  }
  std::fprintf(stderr, "  RT unit    %8.1f ms\n", median(&HybridTimes::traceMs));
  if (hybrid) std::fprintf(stderr, "  compose    %8.1f ms\n", median(&HybridTimes::composeMs));
  std::fprintf(stderr, "  frame      %8.1f ms\n", median(&HybridTimes::totalMs));
}

// --mask all: every pixel through the tile service, no OpenGL.
void renderFullTrace(TileService& service, const FrameSettings& frame, int tileSize, HybridResult& r) {
  const Clock::time_point start = Clock::now();
  FrameOptions frameOptions;
  frameOptions.tileSize = tileSize;
  ProgressBar progress("rendering");
  frameOptions.progress = [&progress](int done, int total) { progress.update(done, total); };
  FrameResult full = renderFrame(service, frame, frameOptions);
  r.image = std::move(full.image);
  r.rays = full.stats;
  r.maskedPixels = static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height);
  r.tiles = static_cast<int>(tileGrid(frame.width, frame.height, tileSize).size());
  r.times.traceMs = r.times.totalMs = msSince(start);
}

// The line on stderr after a render, the medians of --frames N, and a
// warning for discarded samples.
void printSummary(const RenderOptions& options, const FrameSettings& frame, const std::string& where,
                  const std::vector<HybridTimes>& frameTimes, const RayStats& rays, bool hybrid) {
  std::fprintf(stderr, "%s: %dx%d, %d spp, %s: trace %.1f ms, frame %.1f ms, %.2f M rays -> %s\n",
               options.scene.c_str(), frame.width, frame.height, frame.sampling.samples, where.c_str(),
               frameTimes.back().traceMs, frameTimes.back().totalMs, static_cast<double>(rays.total()) / 1e6,
               options.output.c_str());
  if (options.frames > 1) printTimingTable(frameTimes, hybrid);
  if (rays.nonFiniteSamples > 0) {
    std::fprintf(stderr, "warning: %llu samples were not finite and were discarded\n",
                 static_cast<unsigned long long>(rays.nonFiniteSamples));
  }
}

// Each server's share of the last frame, and the provenance image's legend.
void printServers(const DistributionReport& report, bool legend) {
  for (const ServerReport& s : report.servers) {
    std::fprintf(stderr, "  server %-24s %-11s %5zu tiles %9zu pixels  busy %8.1f ms  rtt %6.2f ms%s%s\n",
                 s.address.c_str(), std::string(enumWord(s.state)).c_str(), s.tiles, s.maskedPixels, s.busyMs,
                 s.rttMs, s.why.empty() ? "" : "  ", s.why.c_str());
  }
  if (report.reissuedTiles + report.duplicatedTiles > 0) {
    std::fprintf(stderr, "  %zu tiles re-issued from lost servers, %zu duplicated at the end\n", report.reissuedTiles,
                 report.duplicatedTiles);
  }
  if (legend) std::fprintf(stderr, "provenance: %s\n", provenanceLegend(report).c_str());
}

// An output is refused before anything renders: a PNG option must name a
// .png file, and its folder must exist and be writable.
void checkOutput(const char* option, const std::string& path, bool png) {
  if (path.empty() || path == "-") return;
  const std::filesystem::path p(path);
  std::string extension = p.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  if (png && extension != ".png") {
    throw InputError(std::string(option) + " " + path + ": glint writes PNG; give a file name ending in .png");
  }
  const std::filesystem::path folder = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) {
    throw InputError(std::string(option) + " " + path + ": the folder " + folder.string() + " does not exist");
  }
  if (::access(folder.c_str(), W_OK) != 0) {
    throw InputError(std::string(option) + " " + path + ": the folder " + folder.string() + " is not writable");
  }
}

void checkOutputs(const RenderOptions& o) {
  checkOutput("-o", o.output, true);
  checkOutput("--mask-out", o.maskOut, true);
  checkOutput("--provenance-out", o.provenanceOut, true);
  checkOutput("--stats", o.statsPath, false);
}

}  // namespace

void applyOverrides(const RenderOptions& o, Scene& scene) {
  if (o.eye) scene.frame.camera.eye = *o.eye;
  if (o.lookAt) scene.frame.camera.lookAt = *o.lookAt;
  if (o.up) scene.frame.camera.up = *o.up;
  if (o.fovY) scene.frame.camera.fovY = *o.fovY;
  if (o.width) scene.frame.width = *o.width;
  if (o.height) scene.frame.height = *o.height;
  if (o.pattern) scene.frame.sampling.pattern = *o.pattern;
  if (o.adaptiveThreshold) scene.frame.sampling.adaptiveThreshold = *o.adaptiveThreshold;
  if (o.samples) scene.frame.sampling.samples = *o.samples;
  if (o.filter) scene.frame.sampling.filter = *o.filter;
  if (o.seed) scene.frame.sampling.seed = *o.seed;
  if (o.maxDepth) scene.frame.tracing.maxDepth = *o.maxDepth;
  if (o.minWeight) scene.frame.tracing.minWeight = *o.minWeight;
  const std::string samples = "--samples " + std::to_string(scene.frame.sampling.samples);
  checkFrame(scene.frame, LoadLimits{}.maxImagePixels,
             {.size = "--size",
              .camera = "camera.",
              .samples = samples.c_str(),
              .seed = "--seed",
              .maxDepth = "--max-depth",
              .minWeight = "--min-weight",
              .adaptiveThreshold = "--adaptive-threshold"});
  if (o.mask) scene.mask.rule = *o.mask;
  if (o.maskThreshold) scene.mask.minReflectivity = *o.maskThreshold;
}

void runRender(const RenderOptions& options) {
  const Clock::time_point start = Clock::now();
  checkOutputs(options);
  proto::LoadedBundle loaded = proto::loadSceneBundle(options.scene);
  applyOverrides(options, loaded.scene);
  const FrameSettings frame = loaded.scene.frame;
  const EffectPlan plan = EffectPlan::derive(loaded.scene, frame);
  const std::size_t dropped = loaded.scene.geometry.droppedTriangles();
  const double loadMs = msSince(start);

  // In process (the default) or through a glintd: the same tiles either way.
  const Clock::time_point prepareStart = Clock::now();
  if (!options.provenanceOut.empty() && options.remote.servers.empty()) {
    throw InputError("--provenance-out " + options.provenanceOut + ": shows which server traced each tile; give --server");
  }
  TileBackend backend({options.remote, options.threads, options.bvh, true}, std::move(loaded));
  TileService& service = backend.service();
  const Scene& scene = backend.scene();
  const double prepareMs = msSince(prepareStart);

  // --mask all is the full ray trace: every pixel through the tile service.
  // Other rules draw each frame with OpenGL and trace only the masked pixels.
  const bool hybridPath = scene.mask.rule != MaskRule::kAll || !options.maskOut.empty();
  std::optional<gl::OffscreenContext> context;
  std::optional<gl::RasterScene> raster;
  if (hybridPath) {
    context.emplace(frame.width, frame.height);
    raster.emplace(context->api(), scene);
  }
  std::optional<StatsWriter> stats;
  if (!options.statsPath.empty()) stats.emplace(options.statsPath);
  std::vector<HybridTimes> frameTimes;
  HybridResult r;  // reused: each frame overwrites it
  for (int f = 0; f < options.frames; ++f) {
    if (hybridPath) {
      renderHybrid(context->api(), *raster, service, frame, scene.mask, options.tileSize, r);
    } else {
      renderFullTrace(service, frame, options.tileSize, r);
    }
    if (f == 0 && !options.maskOut.empty()) writeMaskPng(options.maskOut, r.mask, frame.width, frame.height);
    if (stats) {
      stats->write({.frame = f,
                    .width = frame.width,
                    .height = frame.height,
                    .maskedPixels = r.maskedPixels,
                    .tiles = r.tiles,
                    .rays = r.rays,
                    .plan = &plan,
                    .droppedTriangles = dropped,
                    .remote = !options.remote.servers.empty(),
                    .loadMs = loadMs,
                    .prepareMs = prepareMs,
                    .traceMs = r.times.traceMs,
                    .frameMs = r.times.totalMs,
                    .totalMs = f == 0 ? msSince(start) : r.times.totalMs,
                    .hybrid = hybridPath ? std::optional<HybridTimes>(r.times) : std::nullopt,
                    .distribution = backend.distributed() ? &backend.distributed()->lastFrame() : nullptr});
    }
    frameTimes.push_back(r.times);
  }
  writePng(options.output, r.image);
  if (!options.provenanceOut.empty()) {
    writePng(options.provenanceOut, provenanceImage(r.image, backend.distributed()->lastFrame()));
  }

  if (!options.quiet) {
    printSummary(options, frame, backend.where(), frameTimes, r.rays, hybridPath);
    if (backend.distributed()) printServers(backend.distributed()->lastFrame(), !options.provenanceOut.empty());
  }
}

}  // namespace glint
