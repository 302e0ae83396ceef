#include "tests/bench/indirect_section.h"

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
#include "common/metrics/flip.h"
#include "common/render/field_probes.h"
#include "common/render/linear_frame.h"
#include "common/render/prepared_scene.h"
#include "common/render/renderer.h"
#include "common/render/tile_service.h"
#include "common/scene/scene_load.h"
#include "tests/bench/bench_timing.h"

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

LinearImage pathFrame(const PreparedScene& prepared, int samples, double& ms) {
  FrameSettings frame = prepared.scene().frame;
  frame.sampling.samples = samples;
  const Renderer renderer(prepared, frame);
  LinearImage image;
  ms = medianMs(3, [&] {
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
void hybridRows(const PreparedScene& prepared, const LinearImage& displayedReference,
                const std::vector<Point>& displayedCurve, bool quick) {
  const Scene& scene = prepared.scene();
  gl::OffscreenContext context(scene.frame.width, scene.frame.height);
  MaskSettings mask;
  mask.rule = MaskRule::kAuto;
  std::printf("\nThe hybrid frame (2 threads), FLIP as displayed:\n\n");
  std::printf("| field probes, rays | samples | field ms | frame ms | GL ms | traced pixels | mean FLIP | path ms to "
              "that FLIP | path / (field + frame) | path / frame |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
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
      const double ms = medianMs(3, [&] { renderHybrid(context.api(), raster, service, frame, mask, 32, result); });
      const double mean = flipStats(flip(displayedReference, displayedLight(result.image))).mean;
      const double pathMs = pathMsAt(displayedCurve, mean);
      const double traced = 100.0 * static_cast<double>(result.maskedPixels) / static_cast<double>(result.mask.size());
      char path[96] = "past the curve | - | -";
      if (!std::isnan(pathMs)) {
        std::snprintf(path, sizeof path, "%.0f | %.2fx | %.2fx", pathMs, pathMs / (fieldMs + ms), pathMs / ms);
      }
      std::printf("| %d, %d | %d | %.0f | %.0f | %.1f | %.0f%% | %.4f | %s |\n", settings.probes, settings.rays, samples,
                  fieldMs, ms, result.times.rasterMs, traced, mean, path);
    }
  }
}

void sceneRows(const fs::path& file, bool quick) {
  Scene scene = loadSceneFile(file);
  scene.frame.width = quick ? 160 : 640;
  scene.frame.height = quick ? 120 : 480;
  const PreparedScene prepared(std::move(scene), BvhSettings{});
  const Encoder encoder(prepared.scene().frame.output);
  const int referenceSamples = quick ? 256 : 1024;
  double ms = 0.0;
  const LinearImage reference = pathFrame(prepared, referenceSamples, ms);
  const LinearImage displayedReference = displayedLight(reference, encoder);
  std::printf("\n%s, %dx%d, reference: the path trace at %d samples (%.0f ms)\n\n", file.filename().c_str(),
              reference.width, reference.height, referenceSamples, ms);
  std::printf("| path samples | ms | mean FLIP | mean FLIP as displayed |\n|---|---|---|---|\n");
  std::vector<Point> curve, displayedCurve;
  for (int samples = 1; samples <= (quick ? 16 : 64); samples *= 2) {
    const LinearImage image = pathFrame(prepared, samples, ms);
    curve.push_back({ms, meanFlip(reference, image)});
    displayedCurve.push_back({ms, flipStats(flip(displayedReference, displayedLight(image, encoder))).mean});
    std::printf("| %d | %.0f | %.4f | %.4f |\n", samples, ms, curve.back().flip, displayedCurve.back().flip);
  }
  std::printf("\n");
  fieldRows(prepared, reference, curve, quick);
  hybridRows(prepared, displayedReference, displayedCurve, quick);
}

}  // namespace

void indirectSection(const std::string& scenes, bool quick) {
  std::printf("\n## Indirect light: the irradiance field against path tracing, at equal FLIP\n");
  for (const char* name : {"cornell.json", "room-path.json"}) sceneRows(fs::path(scenes) / name, quick);
}

}  // namespace glint::bench
