#include "client/accuracy/accuracy_command.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <tuple>

#include "client/accuracy/accuracy_report.h"
#include "client/accuracy/accuracy_sweep.h"
#include "client/farm/distributed_tile_service.h"
#include "client/raster/hybrid_frame.h"
#include "client/raster/offscreen_context.h"
#include "client/raster/raster_scene.h"
#include "client/commands/scene_warnings.h"
#include "common/base/compute_pool.h"
#include "common/base/error.h"
#include "common/scene/frame_limits.h"
#include "common/image/encoding.h"
#include "common/metrics/flip.h"
#include "common/image/image_write.h"
#include "common/render/effects.h"
#include "common/render/emitter_patches.h"
#include "common/render/field_probes.h"
#include "common/render/linear_frame.h"
#include "common/scene/load_limits.h"
#include "common/base/timing.h"
#include "proto/scene_bundle.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

// The reference: deep recursion, no weight cut-off, jittered samples, and
// 64 points of each area light per sample (times the samples: 16,384 a pixel
// at the default 256).
constexpr int kReferenceDepth = 16;
constexpr int kReferenceLightSamples = 64;
// Under path transport: bounces enough that what they leave out is below
// the reference's noise (a Cornell box's walls reflect at most 0.73).
constexpr int kReferenceBounces = 64;

struct Sweep {
  const PreparedScene& prepared;
  Encoder encoder;  // the scene's output: what a viewer of the images sees
  ThreadPool& pool;
  int frames;
  int tileSize;         // --tile-size
  DistributedTileService* remote;  // --server: the rows' tiles (and fields' batches) go there
  std::optional<gl::GlBackend> gl;                 // --gl
  std::unique_ptr<gl::OffscreenContext> context;  // made for the first hybrid row
  std::unique_ptr<gl::RasterScene> raster;
  // Under path transport: rows may draw from an irradiance field (the
  // emitters few flat ones), each filled once for its settings, in process
  // or by the servers.
  bool fieldDrawable = false;
  struct Filled {
    std::optional<IrradianceField> field;
    double ms = 0.0;  // what filling it took
  };
  std::map<std::tuple<int, int, int, std::uint32_t>, Filled> fields;  // by probes, rays, bounces, seed
};

// Whether a row is a hybrid frame: its key's (hybridKey), where OpenGL can
// draw the row's light (under path transport, from its irradiance field).
bool drawnWithGl(const Sweep& sweep, AccuracyKey key, const FrameSettings& frame) {
  if (!hybridKey(key)) return false;
  return frame.tracing.transport != Transport::kPath || (frame.tracing.field && sweep.fieldDrawable);
}

// The row's irradiance field, filled the first time its settings come.
const Sweep::Filled& fieldOf(Sweep& sweep, const FrameSettings& frame) {
  const FieldSettings& settings = *frame.tracing.field;
  auto [at, fresh] =
      sweep.fields.try_emplace({settings.probes, settings.rays, frame.tracing.maxBounces, frame.sampling.seed});
  if (fresh) {
    const auto start = Clock::now();
    RayStats rays;
    at->second.field.emplace(sweep.remote
                                 ? sweep.remote->fillField(frame, sweep.prepared.scene().geometry.bounds(), settings)
                                 : buildField(sweep.prepared, frame, settings, rays));
    at->second.ms = msSince(start);
  }
  return at->second;
}

// Every setting checked as the frame would check it, before anything renders.
void checkSetting(const std::string& place, FrameSettings frame) {
  const std::string samples = place + " (samples " + std::to_string(frame.sampling.samples) + ")";
  checkFrame(frame, LoadLimits{}.maxImagePixels,
             {.size = "--size", .camera = "camera.", .samples = samples.c_str(), .seed = place.c_str(),
              .maxDepth = place.c_str(), .maxBounces = place.c_str(), .minWeight = place.c_str(), .adaptiveThreshold = place.c_str(),
              .perceptualThreshold = place.c_str(), .lightSamples = place.c_str(), .exposure = "--exposure"});
}

// The scene's pattern where it takes any count and no rule of its own
// (jittered, sobol); jittered otherwise.
SamplePattern referencePattern(SamplePattern scene) {
  return scene == SamplePattern::kSobol ? SamplePattern::kSobol : SamplePattern::kJittered;
}

FrameSettings referenceFrame(FrameSettings frame, int samples, std::uint32_t seed) {
  frame.sampling.pattern = referencePattern(frame.sampling.pattern);
  frame.sampling.samples = samples;
  frame.sampling.seed = seed;
  frame.tracing.maxDepth = kReferenceDepth;
  frame.tracing.minWeight = 0.0f;
  frame.sampling.lightSamples = kReferenceLightSamples;
  frame.tracing.maxBounces = kReferenceBounces;
  return frame;
}

// A full-trace row: the frame `frames` times, the median time, the last image.
LinearImage traceRow(Sweep& sweep, const FrameSettings& frame, AccuracyRow& row) {
  const Renderer renderer(sweep.prepared, frame);
  std::vector<double> times;
  LinearImage image;
  for (int f = 0; f < sweep.frames; ++f) {
    row.rays = {};
    const auto start = Clock::now();
    if (sweep.remote) {
      FrameResult r = renderFrame(*sweep.remote, frame, {.tileSize = sweep.tileSize, .window = {}, .progress = {}});
      row.rays = r.stats;
      image = decodeBytes(r.image, sweep.encoder);
    } else {
      image = renderLinear(renderer, sweep.pool, row.rays, LinearRange::kClamped);
    }
    times.push_back(msSince(start));
  }
  row.timeMs = median(times);
  return image;
}

// A hybrid row (drawnWithGl): OpenGL draws, the tracer fills the mask. Under
// path transport the row's time holds its field's fill beside one frame:
// what a first frame costs.
LinearImage hybridRow(Sweep& sweep, const FrameSettings& frame, const MaskSettings& mask, AccuracyRow& row) {
  if (!sweep.context) {
    sweep.context = std::make_unique<gl::OffscreenContext>(frame.width, frame.height, sweep.gl);
    sweep.raster = std::make_unique<gl::RasterScene>(sweep.context->api(), sweep.prepared.scene());
  }
  const Sweep::Filled* filled = frame.tracing.transport == Transport::kPath ? &fieldOf(sweep, frame) : nullptr;
  if (filled) sweep.raster->useField(*filled->field);
  // The rule all traces path transport in full, as glint render --mask all does.
  const bool readsField = filled && mask.rule != MaskRule::kAll;
  LocalTileService local(sweep.prepared, sweep.pool, readsField ? &*filled->field : nullptr);
  if (sweep.remote) sweep.remote->useField(readsField ? &*filled->field : nullptr);
  TileService& service = sweep.remote ? static_cast<TileService&>(*sweep.remote) : local;
  std::vector<double> times;
  HybridResult result;
  for (int f = 0; f < sweep.frames + 1; ++f) {  // the first compiles the shaders
    renderHybrid(sweep.context->api(), *sweep.raster, service, frame, mask, sweep.tileSize, result);
    if (f > 0) times.push_back(result.times.totalMs);
  }
  if (sweep.remote) sweep.remote->useField(nullptr);  // the next row's frames trace in full
  row.fieldMs = filled ? filled->ms : 0.0;
  row.timeMs = median(times) + row.fieldMs;
  row.rays = result.rays;
  return decodeBytes(result.image, sweep.encoder);
}

// The reference, as traced and as a display shows it (FLIP's input).
struct Reference {
  LinearImage linear;
  LinearImage displayed;
};

// The row's errors against the reference, and its images: the PFM, the
// PNG, the false-colour error and FLIP's map.
void measureRow(const fs::path& dir, const Encoder& encoder, const LinearImage& image, const Reference& reference,
                AccuracyRow& row) {
  row.error = compareImages(image, reference.linear);
  const FlipMap map = flip(reference.displayed, displayedLight(image, encoder));
  row.flip = flipStats(map);
  const std::string stem = row.name + "-" + row.value;
  writePfm(dir / (stem + ".pfm"), image);
  writePng(dir / row.image, encodeBytes(image, encoder), encoder.encoding());
  writePng(dir / (stem + "-error.png"), errorImage(pixelErrors(image, reference.linear), image.width, image.height),
           Encoding::kSrgb);
  writePng(dir / (stem + "-flip.png"), magmaImage(map), Encoding::kSrgb);
}

AccuracyReference renderReference(Sweep& sweep, const FrameSettings& frame, int samples, const fs::path& dir,
                                  Reference& reference) {
  const auto start = Clock::now();
  RayStats ignored;
  const std::string light = frame.tracing.transport == Transport::kPath
                                ? "path transport, " + std::to_string(kReferenceBounces) + " bounces"
                                : "max depth " + std::to_string(kReferenceDepth) + ", no weight cut-off";
  const std::string pattern(enumWord(referencePattern(frame.sampling.pattern)));
  std::fprintf(stderr, "reference: 2 x %d %s samples, %s ...\n", samples / 2, pattern.c_str(), light.c_str());
  const Renderer a(sweep.prepared, referenceFrame(frame, samples / 2, frame.sampling.seed));
  const Renderer b(sweep.prepared, referenceFrame(frame, samples / 2, frame.sampling.seed + 1));
  const LinearImage halfA = renderLinear(a, sweep.pool, ignored, LinearRange::kClamped);
  const LinearImage halfB = renderLinear(b, sweep.pool, ignored, LinearRange::kClamped);
  reference.linear = average(halfA, halfB);
  reference.displayed = displayedLight(reference.linear, sweep.encoder);
  // Each half errs by about sqrt(2) times the whole; their difference by 2 times.
  AccuracyReference r{samples, pattern, light, compareImages(halfA, halfB).rmse / 2.0,
                      flipStats(flip(displayedLight(halfA, sweep.encoder), displayedLight(halfB, sweep.encoder))).mean,
                      msSince(start)};
  std::fprintf(stderr, "reference: its own error about FLIP %.4f, RMSE %.5f (its two halves against each other)\n",
               ownError(r, AccuracyMetric::kFlip), r.ownRmse);
  writePfm(dir / "reference.pfm", reference.linear);
  writePng(dir / "reference.png", encodeBytes(reference.linear, sweep.encoder), sweep.encoder.encoding());
  return r;
}

bool fieldDrawable(const Scene& scene) {
  return EmitterPatches::of(scene, EffectPlan::derive(scene, scene.frame), 0).has_value();
}

// The scene's frame and mask with one setting changed.
std::pair<FrameSettings, MaskSettings> withSetting(const Scene& scene, AccuracyKey key, const std::string& value) {
  std::pair<FrameSettings, MaskSettings> s{scene.frame, scene.mask};
  applySetting(key, value, s.first, s.second);
  return s;
}

// The field's rows need its light drawn: path transport, few flat emitters.
void checkFieldRows(const Series& s, const Scene& scene) {
  if (!fieldKey(s.key)) return;
  const std::string vary = "--vary " + std::string(enumWord(s.key));
  if (scene.frame.tracing.transport != Transport::kPath) {
    throw UsageError(vary + ": the irradiance field carries path transport's light; the scene's transport is "
                            "whitted (give --transport path)");
  }
  if (!fieldDrawable(scene)) {
    throw UsageError(vary + ": the hybrid frame draws the field's light only for at most " +
                     std::to_string(EmitterPatches::kMaxPatches) +
                     " flat emitting triangles of plain emission, and this scene has others");
  }
}

std::vector<Series> sweepOf(const AccuracyOptions& o, const Scene& scene) {
  std::vector<Series> series;
  for (const std::string& v : o.vary) series.push_back(parseVary(v));
  if (series.empty()) series = defaultSweep(scene);
  for (const Series& s : series) {
    checkFieldRows(s, scene);
    for (const std::string& value : s.values) {
      checkSetting("--vary " + std::string(enumWord(s.key)) + "=" + value, withSetting(scene, s.key, value).first);
    }
  }
  if (o.referenceSamples % 2 != 0) {
    throw UsageError("--reference-samples " + std::to_string(o.referenceSamples) +
                     ": must be even (two half-sample references estimate its own error)");
  }
  return series;
}

}  // namespace

void runAccuracy(const AccuracyOptions& o) {
  proto::LoadedBundle loaded = proto::loadSceneBundle(o.scene);
  printSceneWarnings(o.scene, loaded.scene);
  Scene& scene = loaded.scene;
  printNote(applyFrameOverrides(o.frame, scene));
  const std::vector<Series> series = sweepOf(o, scene);
  const fs::path dir(o.outDir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw InputError("-o " + o.outDir + ": cannot make the folder (" + ec.message() + ")");

  const PreparedScene prepared(scene, BvhSettings{});
  ThreadPool& pool = computePool();
  std::unique_ptr<DistributedTileService> remote;
  if (o.remote.any()) remote = connectServers(o.remote, loaded.bundle);
  Sweep sweep{prepared, Encoder(scene.frame.output), pool, o.frames, o.frame.tileSize, remote.get(), o.gl, nullptr,
              nullptr, fieldDrawable(scene), {}};
  Reference reference;
  const AccuracyReference ref = renderReference(sweep, scene.frame, o.referenceSamples, dir, reference);
  const AccuracyMetric metric = o.metric.value_or(AccuracyMetric::kFlip);

  std::size_t total = 0, done = 0;
  for (const Series& s : series) total += s.values.size();
  std::vector<AccuracyRow> rows;
  for (const Series& s : series) {
    for (const std::string& value : s.values) {
      const auto [frame, mask] = withSetting(scene, s.key, value);
      AccuracyRow row{std::string(enumWord(s.key)), value, value == currentValue(s.key, scene.frame, scene.mask),
                      0.0, 0.0, {}, {}, {}, std::string(enumWord(s.key)) + "-" + value + ".png"};
      const LinearImage image =
          drawnWithGl(sweep, s.key, frame) ? hybridRow(sweep, frame, mask, row) : traceRow(sweep, frame, row);
      measureRow(dir, sweep.encoder, image, reference, row);
      std::fprintf(stderr, "[%zu/%zu] %s = %s: %.1f ms, FLIP %.4f, RMSE %.5f%s\n", ++done, total, row.name.c_str(),
                   row.value.c_str(), row.timeMs, row.flip.mean, row.error.rmse,
                   nearTheReferencesNoise(row, ref, metric)
                       ? " (warning: within 2x of the reference's own error; raise --reference-samples)"
                       : "");
      rows.push_back(std::move(row));
    }
  }
  writeCsv(dir, rows);
  const bool plotted = writePlot(dir, rows, ref, metric);
  writeReport(dir, o.scene, ref, rows, metric, plotted);
  std::fprintf(stderr, "wrote %s/report.md, accuracy.csv%s and the images\n", o.outDir.c_str(),
               plotted ? ", accuracy.png" : " (no accuracy.png: gnuplot is not installed; apt-get install gnuplot-nox)");
}

}  // namespace glint
