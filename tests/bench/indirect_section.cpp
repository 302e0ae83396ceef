#include "tests/bench/indirect_section.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "common/base/compute_pool.h"
#include "common/base/timing.h"
#include "common/metrics/flip.h"
#include "common/render/field_probes.h"
#include "common/render/linear_frame.h"
#include "common/render/prepared_scene.h"
#include "common/render/renderer.h"
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

void sceneRows(const fs::path& file, bool quick) {
  Scene scene = loadSceneFile(file);
  scene.frame.width = quick ? 160 : 320;
  scene.frame.height = quick ? 120 : 240;
  const PreparedScene prepared(std::move(scene), BvhSettings{});
  const int referenceSamples = quick ? 256 : 1024;
  double ms = 0.0;
  const LinearImage reference = pathFrame(prepared, referenceSamples, ms);
  std::printf("\n%s, %dx%d, reference: the path trace at %d samples (%.0f ms)\n\n", file.filename().c_str(),
              reference.width, reference.height, referenceSamples, ms);
  std::printf("| path samples | ms | mean FLIP |\n|---|---|---|\n");
  std::vector<Point> curve;
  for (int samples = 1; samples <= (quick ? 16 : 64); samples *= 2) {
    const LinearImage image = pathFrame(prepared, samples, ms);
    curve.push_back({ms, meanFlip(reference, image)});
    std::printf("| %d | %.0f | %.4f |\n", samples, ms, curve.back().flip);
  }
  std::printf("\n");
  fieldRows(prepared, reference, curve, quick);
}

}  // namespace

void indirectSection(const std::string& scenes, bool quick) {
  std::printf("\n## Indirect light: the irradiance field against path tracing, at equal FLIP\n");
  for (const char* name : {"cornell.json", "room-path.json"}) sceneRows(fs::path(scenes) / name, quick);
}

}  // namespace glint::bench
