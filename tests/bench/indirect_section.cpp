#include "tests/bench/indirect_section.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "client/raster/hybrid_frame.h"
#include "client/raster/offscreen_context.h"
#include "client/raster/raster_scene.h"
#include "common/base/compute_pool.h"
#include "common/base/timing.h"
#include "common/image/encoding.h"
#include "common/image/image_read.h"
#include "common/metrics/flip.h"
#include "common/render/field_probes.h"
#include "common/render/linear_frame.h"
#include "common/render/prepared_scene.h"
#include "common/render/renderer.h"
#include "common/render/tile_service.h"
#include "common/scene/scene_load.h"
#include "tests/bench/bench_timing.h"
#include "tests/bench/povray_run.h"

namespace glint::bench {
namespace {

namespace fs = std::filesystem;

struct Point {
  double ms;
  double flip;
};

double meanFlip(const LinearImage& reference, const LinearImage& test) {
  return flipStats(hdrFlip(reference, test, hdrExposures(reference))).mean;
}

// The path trace at `samples`, its time the median of `runs`.
LinearImage pathFrame(const PreparedScene& prepared, int samples, int runs, double& ms) {
  FrameSettings frame = prepared.scene().frame;
  frame.sampling.samples = samples;
  const Renderer renderer(prepared, frame);
  LinearImage image;
  ms = medianMs(runs, [&] {
    RayStats stats;
    image = renderLinear(renderer, computePool(), stats, LinearRange::kUnbounded);
  });
  return image;
}

// The path trace's time to reach `flip`, between the two measured sample
// counts around it (log-linear in both); NaN past the curve's ends.
double pathMsAt(const std::vector<Point>& curve, double flip) {
  for (std::size_t i = 1; i < curve.size(); ++i) {
    const Point& a = curve[i - 1];
    const Point& b = curve[i];
    if (flip > a.flip || flip < b.flip) continue;
    const double t = (std::log(a.flip) - std::log(flip)) / (std::log(a.flip) - std::log(b.flip));
    return std::exp(std::log(a.ms) + t * (std::log(b.ms) - std::log(a.ms)));
  }
  return NAN;
}

void fieldRows(const PreparedScene& prepared, const LinearImage& reference, const std::vector<Point>& curve,
               bool quick) {
  std::printf("| field probes, rays | samples | field ms | frame ms | undecided samples | mean FLIP | path ms to that FLIP | path / field |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  const Scene& scene = prepared.scene();
  for (const FieldSettings settings : {FieldSettings{8, 256}, FieldSettings{8, 1024}, FieldSettings{16, 256}}) {
    if (quick && settings.probes > 8) continue;
    for (const int samples : {1, 4}) {
      FrameSettings frame = scene.frame;
      frame.sampling.samples = samples;
      RayStats fieldStats, stats;
      Clock::time_point start = Clock::now();
      const IrradianceField field = buildField(prepared, frame, settings, fieldStats);
      const double fieldMs = msSince(start);
      const Renderer renderer(prepared, frame, EffectPlan::derive(scene, frame), &field);
      start = Clock::now();
      const LinearImage image = renderLinear(renderer, computePool(), stats, LinearRange::kUnbounded);
      const double frameMs = msSince(start);
      const double flip = meanFlip(reference, image);
      const double pathMs = pathMsAt(curve, flip);
      char path[64] = "past the curve | -";
      if (!std::isnan(pathMs)) std::snprintf(path, sizeof path, "%.0f | %.2fx", pathMs, pathMs / (fieldMs + frameMs));
      std::printf("| %d, %d | %d | %.0f | %.0f | %llu | %.4f | %s |\n", settings.probes, settings.rays, samples,
                  fieldMs, frameMs, static_cast<unsigned long long>(stats.fieldUndecided), flip, path);
    }
  }
}

// The hybrid frame with the field: OpenGL draws the field's light, the
// tracer the emitters' penumbra, the pixels the field cannot decide and the
// edges; FLIP as displayed (8-bit), against the path trace's curve as
// displayed. The field is built once and reused for every frame after.
std::vector<Point> hybridRows(const PreparedScene& prepared, const LinearImage& displayedReference,
                              const std::vector<Point>& displayedCurve, bool quick) {
  const Scene& scene = prepared.scene();
  gl::OffscreenContext context(scene.frame.width, scene.frame.height);
  MaskSettings mask;
  mask.rule = MaskRule::kAuto;
  std::printf("\nThe hybrid frame (2 threads), FLIP as displayed:\n\n");
  std::printf("| field probes, rays | samples | field ms | frame ms | raster ms | GL pass ms | traced pixels | mean "
              "FLIP | path ms to that FLIP | path / (field + frame) | path / frame |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<Point> firstFrames;
  for (const FieldSettings settings : {FieldSettings{8, 256}, FieldSettings{8, 1024}}) {
    if (quick && settings.rays > 256) continue;
    FrameSettings frame = scene.frame;
    RayStats fieldStats;
    const Clock::time_point start = Clock::now();
    const IrradianceField field = buildField(prepared, frame, settings, fieldStats);
    const double fieldMs = msSince(start);
    ThreadPool pool(2);
    LocalTileService service(prepared, pool, &field);
    gl::RasterScene raster(context.api(), scene);
    raster.useField(field);
    for (const int samples : {1, 4}) {
      frame.sampling.samples = samples;
      HybridResult result;
      std::vector<double> rasterMs, glPassMs;  // GL pass: raster + readback (the marks, the proofs) + compose
      const double ms = medianMs(3, [&] {
        renderHybrid(context.api(), raster, service, frame, mask, 32, result);
        rasterMs.push_back(result.times.rasterMs);
        glPassMs.push_back(result.times.rasterMs + result.times.readbackMs + result.times.composeMs);
      });
      const double mean = flipStats(flip(displayedReference, displayedLight(result.image))).mean;
      firstFrames.push_back({fieldMs + ms, mean});
      const double pathMs = pathMsAt(displayedCurve, mean);
      const double traced = 100.0 * static_cast<double>(result.maskedPixels) / static_cast<double>(result.mask.size());
      char path[96] = "past the curve | - | -";
      if (!std::isnan(pathMs)) {
        std::snprintf(path, sizeof path, "%.0f | %.2fx | %.2fx", pathMs, pathMs / (fieldMs + ms), pathMs / ms);
      }
      std::printf("| %d, %d | %d | %.0f | %.0f | %.1f | %.1f | %.0f%% | %.4f | %s |\n", settings.probes, settings.rays,
                  samples, fieldMs, ms, median(rasterMs), median(glPassMs), traced, mean, path);
    }
  }
  return firstFrames;
}

// POV-Ray 3.7's settings tried: its radiosity's `count` (rays a sample) and
// `error_bound` (how far a sample is reused), and 1 or 4 jittered samples a
// pixel.
struct RadiositySetting {
  int count;
  double errorBound;
  bool antialias;
};

constexpr RadiositySetting kRadiositySettings[] = {
    {35, 1.8, false}, {35, 1.8, true}, {100, 1.0, true}, {400, 0.3, true}};

// The fastest of `points` whose FLIP is at most `flip`; none: ms negative.
Point fastestWithin(const std::vector<Point>& points, double flip) {
  Point best{-1.0, NAN};
  for (const Point& p : points) {
    if (p.flip <= flip && (best.ms < 0.0 || p.ms < best.ms)) best = p;
  }
  return best;
}

void radiositySummary(const std::vector<Point>& pov, const std::vector<Point>& hybrid) {
  if (pov.empty() || hybrid.empty()) return;
  const auto byFlip = [](const Point& a, const Point& b) { return a.flip < b.flip; };
  const auto byMs = [](const Point& a, const Point& b) { return a.ms < b.ms; };
  const Point closest = *std::min_element(hybrid.begin(), hybrid.end(), byFlip);
  const Point reaching = fastestWithin(pov, closest.flip);
  if (reaching.ms >= 0.0) {
    std::printf("\nPOV-Ray's fastest setting that reaches the hybrid frame's FLIP %.4f takes %.0f ms: the hybrid frame "
                "(%.0f ms, its field filled in it) is **%.2fx** faster.\n",
                closest.flip, reaching.ms, closest.ms, reaching.ms / closest.ms);
    return;
  }
  const Point fastestPov = *std::min_element(pov.begin(), pov.end(), byMs);
  const Point hybridWithin = fastestWithin(hybrid, fastestPov.flip);
  std::printf("\nNo POV-Ray setting reaches the hybrid frame's FLIP %.4f.", closest.flip);
  if (hybridWithin.ms < 0.0) return (void)std::printf("\n");
  std::printf(" POV-Ray's fastest (%.0f ms, FLIP %.4f) against the hybrid frame's fastest first frame at a FLIP no "
              "higher (%.0f ms, %.4f): **%.2fx**.\n",
              fastestPov.ms, fastestPov.flip, hybridWithin.ms, hybridWithin.flip, fastestPov.ms / hybridWithin.ms);
}

// POV-Ray 3.7's radiosity rendering the scene's .pov (which reads Count and
// ErrorBound) into a PNG encoded as the scene's are, its FLIP as displayed
// against the same converged path trace, and the hybrid frame's first frames
// (`hybrid`) against it at equal FLIP.
void radiosityRows(const fs::path& pov, Encoding encoding, const LinearImage& displayedReference,
                   const std::vector<Point>& hybrid, bool quick) {
  std::printf("\nPOV-Ray 3.7's radiosity on the same scene (%s, 2 threads), FLIP as displayed:\n\n",
              pov.filename().c_str());
  std::printf("| count | error_bound | samples | render ms (radiosity + trace) | process ms | mean FLIP |\n");
  std::printf("|---|---|---|---|---|---|\n");
  const fs::path out = fs::temp_directory_path() / "glint-bench-radiosity.png";
  std::vector<Point> rows;
  for (const RadiositySetting& s : kRadiositySettings) {
    if (quick && s.count > 35) continue;
    const std::string options = std::string(s.antialias ? "+A0.0 +AM1 +R2 +J1.0" : "-A") +
                                (encoding == Encoding::kSrgb ? " File_Gamma=sRGB" : " File_Gamma=1.0") +
                                " Declare=Count=" + std::to_string(s.count) +
                                " Declare=ErrorBound=" + std::to_string(s.errorBound);
    std::vector<double> render, process;
    for (int run = 0; run < (quick ? 1 : 3); ++run) {
      const PovrayRun r = runPovray(pov, out, displayedReference.width, displayedReference.height, options);
      if (r.renderMs < 0.0) return (void)std::printf("POV-Ray failed on %s (%s).\n", pov.c_str(), options.c_str());
      render.push_back(r.renderMs);
      process.push_back(r.processMs);
    }
    const double mean = flipStats(flip(displayedReference, displayedLight(readImageFile(out)))).mean;
    rows.push_back({median(render), mean});
    std::printf("| %d | %.1f | %d | %.0f | %.0f | %.4f |\n", s.count, s.errorBound, s.antialias ? 4 : 1,
                rows.back().ms, median(std::move(process)), mean);
  }
  fs::remove(out);
  radiositySummary(rows, hybrid);
}

void sceneRows(const fs::path& file, bool quick, bool povray) {
  Scene scene = loadSceneFile(file);
  scene.frame.width = quick ? 160 : 640;
  scene.frame.height = quick ? 120 : 480;
  const PreparedScene prepared(std::move(scene), BvhSettings{});
  const Encoder encoder(prepared.scene().frame.output);
  const int referenceSamples = quick ? 256 : 1024;
  double ms = 0.0;
  const LinearImage reference = pathFrame(prepared, referenceSamples, 1, ms);  // its time is only shown
  const LinearImage displayedReference = displayedLight(reference, encoder);
  std::printf("\n%s, %dx%d, reference: the path trace at %d samples (%.0f ms)\n\n", file.filename().c_str(),
              reference.width, reference.height, referenceSamples, ms);
  std::printf("| path samples | ms | mean FLIP | mean FLIP as displayed |\n|---|---|---|---|\n");
  std::vector<Point> curve, displayedCurve;
  for (int samples = 1; samples <= (quick ? 16 : 64); samples *= 2) {
    const LinearImage image = pathFrame(prepared, samples, 3, ms);
    curve.push_back({ms, meanFlip(reference, image)});
    displayedCurve.push_back({ms, flipStats(flip(displayedReference, displayedLight(image, encoder))).mean});
    std::printf("| %d | %.0f | %.4f | %.4f |\n", samples, ms, curve.back().flip, displayedCurve.back().flip);
  }
  std::printf("\n");
  fieldRows(prepared, reference, curve, quick);
  const std::vector<Point> hybrid = hybridRows(prepared, displayedReference, displayedCurve, quick);
  const fs::path pov = fs::path(file).replace_extension(".pov");
  if (povray && fs::exists(pov)) {
    radiosityRows(pov, prepared.scene().frame.output.encoding, displayedReference, hybrid, quick);
  }
}

}  // namespace

void indirectSection(const std::string& scenes, bool quick, bool povray) {
  std::printf("\n## Indirect light: the irradiance field against path tracing, at equal FLIP\n");
  const bool withPovray = povray && povrayInstalled();
  for (const char* name : {"cornell.json", "room-path.json"}) sceneRows(fs::path(scenes) / name, quick, withPovray);
}

}  // namespace glint::bench
