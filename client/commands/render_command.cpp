#include "client/commands/render_command.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "client/farm/distributed_tile_service.h"
#include "client/raster/hybrid_frame.h"
#include "client/raster/offscreen_context.h"
#include "client/commands/output_file.h"
#include "client/commands/progress.h"
#include "client/commands/provenance.h"
#include "client/raster/raster_scene.h"
#include "client/commands/scene_warnings.h"
#include "client/commands/stats_json.h"
#include "client/farm/tile_backend.h"
#include "common/base/error.h"
#include "common/base/timing.h"
#include "common/image/encoding.h"
#include "common/image/image_write.h"
#include "common/render/frame.h"
#include "common/render/linear_frame.h"
#include "common/scene/frame_limits.h"
#include "common/scene/load_limits.h"
#include "common/scene/scene_load.h"
#include "proto/scene_bundle.h"

namespace glint {
namespace {

// The mask as the thesis's figures show it: white where the tracer fills.
void writeMaskPng(const std::string& path, const std::vector<std::uint8_t>& mask, int width, int height) {
  FrameImage image{width, height, std::vector<std::uint8_t>(mask.size() * 3)};
  for (std::size_t i = 0; i < mask.size(); ++i)
    image.rgb[3 * i] = image.rgb[3 * i + 1] = image.rgb[3 * i + 2] = mask[i] ? 255 : 0;
  writePng(path, image, Encoding::kSrgb);
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

// How a frame's progress shows, and what it is called.
struct FrameProgress {
  ProgressMode mode;
  std::string label;
};

ProgressMode progressMode(const RenderOptions& options) {
  return options.quiet ? ProgressMode::kQuiet : options.progress ? ProgressMode::kForced : ProgressMode::kAuto;
}

FrameProgress frameProgress(const RenderOptions& options, int frame) {
  const ProgressMode mode = progressMode(options);
  if (options.frames == 1) return {mode, "rendering"};
  return {mode, "frame " + std::to_string(frame + 1) + " of " + std::to_string(options.frames)};
}

// Shows a step's progress on `line`, with each server's share where `backend` has servers.
std::function<void(int, int)> showOn(ProgressLine& line, const TileBackend* backend = nullptr) {
  ProgressLine::Shares shares;
  if (const DistributedTileService* farm = backend ? backend->distributed() : nullptr) {
    shares = [farm] { return farm->tracedShares(); };
  }
  return [&line, shares](int done, int total) { line.update(done, total, shares, ProgressLine::Clock::now()); };
}

// A hybrid frame, its traced tiles' progress shown.
void renderHybridFrame(TileBackend& backend, gl::OffscreenContext& context, gl::RasterScene& raster,
                       const FrameSettings& frame, const FrameProgress& shown, const RenderOptions& options,
                       HybridResult& r) {
  ProgressLine progress = stderrProgress(shown.mode, shown.label);
  const HybridControl control{.cancelled = {}, .progress = showOn(progress, &backend)};
  renderHybrid(context.api(), raster, backend.service(), frame, backend.scene().mask, options.frame.tileSize, r,
               options.crop, control);
}

// --mask all: every pixel (of the crop window) through the tile service, no
// OpenGL.
void renderFullTrace(TileBackend& backend, const FrameSettings& frame, FrameOptions frameOptions,
                     const FrameProgress& shown, HybridResult& r) {
  const Clock::time_point start = Clock::now();
  ProgressLine progress = stderrProgress(shown.mode, shown.label);
  frameOptions.progress = showOn(progress, &backend);
  FrameResult full = renderFrame(backend.service(), frame, frameOptions);
  r.image = std::move(full.image);
  r.rays = full.stats;
  const TileRect window = frameWindow(frame, frameOptions);
  r.maskedPixels = window.pixelCount();
  r.tiles = static_cast<int>(tileGrid(window, frameOptions.tileSize).size());
  r.times.traceMs = r.times.totalMs = msSince(start);
}

// The same in process for a float output: the tracer's linear values, not
// clamped, scaled by the exposure.
LinearImage renderFullTraceLinear(TileBackend& backend, const FrameSettings& frame, FrameOptions frameOptions,
                                  const FrameProgress& shown, HybridResult& r) {
  const Clock::time_point start = Clock::now();
  ProgressLine progress = stderrProgress(shown.mode, shown.label);
  frameOptions.progress = showOn(progress, &backend);
  const Renderer renderer(*backend.prepared(), frame);
  r.rays = RayStats{};
  LinearImage image = renderLinear(renderer, *backend.pool(), r.rays, LinearRange::kUnbounded, frameOptions);
  const float scale = Encoder(frame.output).scale();
  for (float& v : image.rgb) v *= scale;
  const TileRect window = frameWindow(frame, frameOptions);
  r.maskedPixels = window.pixelCount();
  r.tiles = static_cast<int>(tileGrid(window, frameOptions.tileSize).size());
  r.times.traceMs = r.times.totalMs = msSince(start);
  return image;
}

// The line on stderr after a render, the medians of --frames N, and a
// warning for discarded samples.
void printSummary(const RenderOptions& options, const FrameSettings& frame, const std::string& where,
                  const std::vector<HybridTimes>& frameTimes, const RayStats& rays, bool hybrid) {
  std::fprintf(stderr, "%s: %dx%d, %d spp, %s: trace %.1f ms, frame %.1f ms, %.2f M rays -> %s\n",
               options.scene.c_str(), frame.width, frame.height, frame.sampling.samples, where.c_str(),
               frameTimes.back().traceMs, frameTimes.back().totalMs, static_cast<double>(rays.total()) / 1e6,
               options.output.c_str());
  if (rays.paths > 0) {
    std::fprintf(stderr, "paths: %.2f bounces a path, %llu the longest, %.2f M light samples\n",
                 static_cast<double>(rays.pathBounces) / static_cast<double>(rays.paths),
                 static_cast<unsigned long long>(rays.longestPath), static_cast<double>(rays.lightSamples) / 1e6);
  }
  if (options.frames > 1) printTimingTable(frameTimes, hybrid);
  if (rays.nonFiniteSamples > 0) {
    std::fprintf(stderr, "warning: %llu samples were not finite and were discarded\n",
                 static_cast<unsigned long long>(rays.nonFiniteSamples));
  }
}

// The irradiance field, filled once before the first frame: what it cost,
// and through servers, each one's batches.
void printFieldFill(const TileBackend& backend) {
  const IrradianceField* field = backend.field();
  if (!field) return;
  std::fprintf(stderr, "irradiance field: %d probes x %d rays, filled once for every frame: %.1f ms, %.2f M rays\n",
               field->probeCount(), field->settings().rays, backend.fieldFill().ms,
               static_cast<double>(backend.fieldFill().rays.total()) / 1e6);
  if (!backend.distributed()) return;
  for (const ServerReport& s : backend.distributed()->fieldReport().servers) {
    std::fprintf(stderr, "  server %-24s %-11s %5zu batches %7zu probes  busy %8.1f ms\n", s.address.c_str(),
                 std::string(enumWord(s.state)).c_str(), s.tiles, s.probes, s.busyMs);
  }
}

// Each server's share of the last frame, and the provenance image's legend
// (with the field's batches, where the servers filled one: `field`).
void printServers(const DistributionReport& report, bool legend, const DistributionReport* field) {
  for (const ServerReport& s : report.servers) {
    const std::string state = std::string(enumWord(s.state)) + (s.joined ? ", new" : "");
    std::fprintf(stderr, "  server %-24s %-11s %5zu tiles %9zu pixels  busy %8.1f ms  rtt %6.2f ms%s%s\n",
                 s.address.c_str(), state.c_str(), s.tiles, s.maskedPixels, s.busyMs, s.rttMs,
                 s.why.empty() ? "" : "  ", s.why.c_str());
  }
  if (report.reissuedTiles + report.duplicatedTiles > 0) {
    std::fprintf(stderr, "  %zu tiles re-issued from lost servers, %zu copied to a second server (%zu of them hedged)\n",
                 report.reissuedTiles, report.duplicatedTiles, report.hedgedTiles);
  }
  if (legend) std::fprintf(stderr, "provenance: %s\n", provenanceLegend(report, field).c_str());
}

// An output is refused before anything renders: an image option must name a
// format glint writes (only PNG where `png`), and its folder must exist and
// be writable.
void checkOutput(const char* option, const std::string& path, bool image, bool png) {
  if (path.empty() || path == "-") return;
  const std::filesystem::path p(path);
  if (image && outputFormat(option, p) != OutputFormat::kPng && png) {
    throw UsageError(std::string(option) + " " + path + ": this image is 8-bit; give a file name ending in .png");
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

// Returns the format -o names.
OutputFormat checkOutputs(const RenderOptions& o) {
  checkOutput("-o", o.output, true, false);
  checkOutput("--mask-out", o.maskOut, true, true);
  checkOutput("--provenance-out", o.provenanceOut, true, true);
  checkOutput("--stats", o.statsPath, false, false);
  const OutputFormat format = outputFormat("-o", o.output);
  return format;
}

// The crop window lies inside the frame.
void checkCrop(const TileRect& crop, const FrameSettings& frame) {
  if (crop.x + crop.width > frame.width || crop.y + crop.height > frame.height) {
    throw UsageError("--crop " + std::to_string(crop.x) + "," + std::to_string(crop.y) + "," +
                     std::to_string(crop.x + crop.width) + "," + std::to_string(crop.y + crop.height) +
                     ": the window must lie inside the " + std::to_string(frame.width) + "x" +
                     std::to_string(frame.height) + " frame");
  }
}

}  // namespace

void applyOverrides(const RenderOptions& o, Scene& scene) {
  const std::string note = applyFrameOverrides(o.frame, scene);
  if (!o.quiet) printNote(note);
  if (o.crop) checkCrop(*o.crop, scene.frame);
}

namespace {

// What runRender keeps between its steps.
struct RenderRun {
  explicit RenderRun(const RenderOptions& o) : options(o) {}
  const RenderOptions& options;
  Clock::time_point start = Clock::now();
  OutputFormat format = OutputFormat::kPng;  // of -o
  FrameSettings frame;
  EffectPlan plan;
  std::size_t dropped = 0;
  double loadMs = 0.0;
  double prepareMs = 0.0;  // the field's fill aside
  std::optional<FrameRecord::Field> field;
};

// --mask all is the full ray trace: every pixel through the tile service.
// Other rules draw each frame with OpenGL and trace only the masked pixels.
bool drawsWithGl(const Scene& scene, const RenderOptions& options) {
  return scene.mask.rule != MaskRule::kAll || !options.maskOut.empty();
}

// Renders options.frames frames into `r` (the last one stays), writing the
// stats of each; the float output's image when the tracer's own values
// are at hand (in process, the full trace).
std::optional<LinearImage> renderFrames(const RenderRun& run, TileBackend& backend, HybridResult& r,
                                        std::vector<HybridTimes>& frameTimes) {
  const RenderOptions& options = run.options;
  const FrameSettings& frame = run.frame;
  const Scene& scene = backend.scene();
  const bool hybridPath = drawsWithGl(scene, options);
  const bool linear = !hybridPath && backend.prepared() && holdsFloats(run.format);
  std::optional<gl::OffscreenContext> context;
  std::optional<gl::RasterScene> raster;
  if (hybridPath) {
    context.emplace(frame.width, frame.height, options.gl);
    raster.emplace(context->api(), scene);
    if (backend.field()) raster->useField(*backend.field());
  }
  std::optional<StatsWriter> stats;
  if (!options.statsPath.empty()) stats.emplace(options.statsPath);
  std::optional<LinearImage> image;
  const FrameOptions frameOptions{.tileSize = options.frame.tileSize, .window = options.crop, .progress = {}};
  for (int f = 0; f < options.frames; ++f) {
    if (hybridPath) {
      renderHybridFrame(backend, *context, *raster, frame, frameProgress(options, f), options, r);
    } else if (linear) {
      image = renderFullTraceLinear(backend, frame, frameOptions, frameProgress(options, f), r);
    } else {
      renderFullTrace(backend, frame, frameOptions, frameProgress(options, f), r);
    }
    if (f == 0 && !options.maskOut.empty()) writeMaskPng(options.maskOut, r.mask, frame.width, frame.height);
    if (stats) {
      stats->write({.frame = f,
                    .width = frame.width,
                    .height = frame.height,
                    .samples = frame.sampling.samples,
                    .crop = options.crop,
                    .maskedPixels = r.maskedPixels,
                    .outOfFocusPixels = r.outOfFocusPixels,
                    .shadowEdgePixels = r.shadowEdgePixels,
                    .rasterEdgePixels = r.rasterEdgePixels,
                    .tiles = r.tiles,
                    .rays = r.rays,
                    .plan = &run.plan,
                    .droppedTriangles = run.dropped,
                    .remote = options.remote.any(),
                    .loadMs = run.loadMs,
                    .prepareMs = run.prepareMs,
                    .field = run.field,
                    .traceMs = r.times.traceMs,
                    .frameMs = r.times.totalMs,
                    .totalMs = f == 0 ? msSince(run.start) : r.times.totalMs,
                    .hybrid = hybridPath ? std::optional<HybridTimes>(r.times) : std::nullopt,
                    .distribution = backend.distributed() ? &backend.distributed()->lastFrame() : nullptr});
    }
    frameTimes.push_back(r.times);
  }
  return image;
}

// Writes -o (and --provenance-out). A float output of an 8-bit frame (a
// hybrid frame, or tiles from servers) holds the light its values stand for.
void writeOutputs(const RenderRun& run, TileBackend& backend, const HybridResult& r,
                  const std::optional<LinearImage>& linear) {
  const RenderOptions& options = run.options;
  const OutputFormat format = run.format;
  const Encoder encoder(run.frame.output);
  if (holdsFloats(format) && !linear) {
    writeOutput(options.output, format, r.image, scaledLight(r.image, encoder), encoder.encoding());
    if (!options.quiet) {
      std::fprintf(stderr,
                   "note: %s holds the 8-bit frame's values decoded to linear light (a hybrid frame or tiles from "
                   "servers); --mask all in process writes the tracer's own floats\n",
                   options.output.c_str());
    }
  } else {
    writeOutput(options.output, format, r.image, linear ? *linear : LinearImage{}, encoder.encoding());
  }
  if (!options.provenanceOut.empty()) {
    writePng(options.provenanceOut, provenanceImage(r.image, backend.distributed()->lastFrame()), encoder.encoding());
  }
}

}  // namespace

void runRender(const RenderOptions& options) {
  RenderRun run(options);
  run.format = checkOutputs(options);
  proto::LoadedBundle loaded = proto::loadSceneBundle(options.scene);
  printSceneWarnings(options.scene, loaded.scene);
  applyOverrides(options, loaded.scene);
  run.frame = loaded.scene.frame;
  run.plan = EffectPlan::derive(loaded.scene, run.frame);
  run.dropped = loaded.scene.geometry.droppedTriangles();
  run.loadMs = msSince(run.start);

  // In process (the default) or through a glintd: the same tiles either way.
  const Clock::time_point prepareStart = Clock::now();
  if (!options.provenanceOut.empty() && !options.remote.any()) {
    throw UsageError("--provenance-out " + options.provenanceOut +
                     ": shows which server traced each tile; give --server");
  }
  if (!options.provenanceOut.empty() && options.crop) {
    throw UsageError("--provenance-out " + options.provenanceOut + ": shows the whole frame; it cannot go with --crop");
  }
  // The hybrid frame under path transport reads the irradiance field, filled here once for every frame
  // (applyOverrides left a rule other than all only where the raster can draw it).
  const bool field =
      loaded.scene.frame.tracing.transport == Transport::kPath && loaded.scene.mask.rule != MaskRule::kAll;
  ProgressLine probes = stderrProgress(progressMode(options), "irradiance field", "probes");
  TileBackend backend({options.remote, options.bvh, true, field, showOn(probes)}, std::move(loaded));
  probes.clear();
  run.prepareMs = msSince(prepareStart) - backend.fieldFill().ms;
  if (const IrradianceField* f = backend.field()) {
    run.field = FrameRecord::Field{f->probeCount(), f->settings().rays, backend.fieldFill().ms, backend.fieldFill().rays};
  }

  std::vector<HybridTimes> frameTimes;
  HybridResult r;  // reused: each frame overwrites it
  const std::optional<LinearImage> linear = renderFrames(run, backend, r, frameTimes);
  writeOutputs(run, backend, r, linear);
  if (!options.quiet) {
    printSummary(options, run.frame, backend.where(), frameTimes, r.rays, drawsWithGl(backend.scene(), options));
    printFieldFill(backend);
    if (backend.distributed()) {
      const DistributionReport* field = backend.field() ? &backend.distributed()->fieldReport() : nullptr;
      printServers(backend.distributed()->lastFrame(), !options.provenanceOut.empty(), field);
    }
  }
}

}  // namespace glint
