#include "tests/bench/transport_section.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/base/thread_pool.h"
#include "common/base/timing.h"
#include "common/metrics/flip.h"
#include "common/metrics/image_metrics.h"
#include "common/image/image_read.h"
#include "common/math/float_bits.h"
#include "common/render/linear_frame.h"
#include "common/render/prepared_scene.h"
#include "common/scene/camera.h"
#include "common/scene/scene_load.h"

namespace glint::bench {
namespace {

namespace fs = std::filesystem;

struct Frame {
  LinearImage image;
  double seconds = 0.0;
};

// The settings both renderers get: a box filter one pixel wide (each pixel
// its own samples' mean), `samples` a pixel (Glint's in the scene's pattern).
Scene transportScene(const fs::path& file, int size, int samples) {
  Scene scene = loadSceneFile(file);
  scene.frame.width = scene.frame.height = size;
  scene.frame.sampling.filter = FilterType::kBox;
  scene.frame.sampling.samples = samples;
  return scene;
}

Frame glintFrame(const PreparedScene& prepared, ThreadPool& pool) {
  const Renderer renderer(prepared, prepared.scene().frame);
  RayStats stats;
  const Clock::time_point start = Clock::now();
  LinearImage image = renderLinear(renderer, pool, stats, LinearRange::kUnbounded);
  return {std::move(image), msSince(start) / 1e3};
}

// Cycles' frame of the scene file (at the size asked), through Blender's
// Python; its time is the render call's, as the script measures it.
std::optional<Frame> cyclesFrame(const fs::path& script, const fs::path& sceneFile, const fs::path& out, int samples,
                                 int bounces, int seed) {
  const std::string command = "blender -b --factory-startup --python '" + script.string() + "' -- '" +
                              sceneFile.string() + "' '" + out.string() + "' " + std::to_string(samples) + " " +
                              std::to_string(bounces) + " " + std::to_string(seed) + " 2>&1";
  const std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return std::nullopt;
  char line[4096];
  std::optional<double> seconds;
  while (std::fgets(line, sizeof line, pipe.get())) {
    double s = 0.0;
    if (std::sscanf(line, "cycles: %*d samples, %*d bounces, %lf s", &s) == 1) seconds = s;
  }
  if (!seconds || !fs::exists(out)) return std::nullopt;
  return Frame{readImageFile(out).values, *seconds};
}

// Mean radiance of each material's pixels (those whose centre sees it).
std::map<std::string, glm::dvec3> surfaceMeans(const PreparedScene& prepared, const LinearImage& image) {
  const Scene& scene = prepared.scene();
  const Camera camera(scene.frame.camera, image.width, image.height);
  std::map<std::string, glm::dvec3> sums;
  std::map<std::string, int> counts;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const Ray ray = camera.generateRay({static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f});
      const std::optional<Hit> hit = prepared.bvh().intersect(ray, kInfinity);
      if (!hit) continue;
      const std::string& name = scene.materials[scene.geometry.materialOf(hit->prim)].name;
      const float* p = &image.rgb[(static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                                   static_cast<std::size_t>(x)) * 3];
      sums[name] += glm::dvec3(p[0], p[1], p[2]);
      ++counts[name];
    }
  }
  for (auto& [name, sum] : sums) sum /= static_cast<double>(counts[name]);
  return sums;
}

double meanFlip(const LinearImage& reference, const LinearImage& test) {
  return flipStats(hdrFlip(reference, test, hdrExposures(reference))).mean;
}

// Each renderer's frames, run in turn (Glint, Cycles, Glint, ...) so that
// the host's slower minutes fall on both: Cycles' first two seeds give the
// noise floor, the times are medians.
struct Runs {
  std::vector<Frame> glint, cycles;
};

std::vector<double> secondsOf(const std::vector<Frame>& frames) {
  std::vector<double> s;
  for (const Frame& f : frames) s.push_back(f.seconds);
  return s;
}

std::string listed(const std::vector<double>& seconds) {
  std::string text;
  for (double s : seconds) {
    char one[32];
    std::snprintf(one, sizeof one, "%s%.1f", text.empty() ? "" : ", ", s);
    text += one;
  }
  return text;
}

void printComparison(const PreparedScene& prepared, const Runs& runs) {
  const LinearImage& reference = runs.cycles[0].image;
  const LinearImage& glint = runs.glint[0].image;
  const double floor = meanFlip(reference, runs.cycles[1].image), glintFlip = meanFlip(reference, glint);
  const double cyclesS = median(secondsOf(runs.cycles)), glintS = median(secondsOf(runs.glint));
  std::printf("| renderer | render s, median (runs) | mean HDR-FLIP against Cycles, seed 0 | RMSE |\n|---|---|---|---|\n");
  std::printf("| Cycles, seeds 0 to %zu | %.2f (%s) | | |\n", runs.cycles.size() - 1, cyclesS,
              listed(secondsOf(runs.cycles)).c_str());
  std::printf("| Cycles, seed 1 (the noise floor) | | %.4f | %.5f |\n", floor,
              compareImages(runs.cycles[1].image, reference).rmse);
  std::printf("| Glint | %.2f (%s) | %.4f | %.5f |\n\n", glintS, listed(secondsOf(runs.glint)).c_str(), glintFlip,
              compareImages(glint, reference).rmse);
  std::printf("Glint: %.2fx Cycles' speed (medians); its FLIP %.2fx the noise floor's\n\n", cyclesS / glintS,
              glintFlip / floor);
  std::printf("| surface | Cycles (R, G, B) | Glint (R, G, B) | Glint / Cycles - 1, luminance |\n|---|---|---|---|\n");
  const auto theirs = surfaceMeans(prepared, reference), ours = surfaceMeans(prepared, glint);
  const auto luminance = [](const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  for (const auto& [name, c] : theirs) {
    const glm::dvec3 g = ours.at(name);
    std::printf("| %s | %.4f, %.4f, %.4f | %.4f, %.4f, %.4f | %+.2f %% |\n", name.c_str(), c.r, c.g, c.b, g.r, g.g,
                g.b, 100.0 * (luminance(g) / luminance(c) - 1.0));
  }
}

}  // namespace

void transportSection(const std::string& scenes, bool quick) {
  const int size = quick ? 64 : 128, samples = quick ? 64 : 4096;
  const fs::path sceneFile = fs::path(scenes) / "cornell.json";
  const PreparedScene prepared(transportScene(sceneFile, size, samples), BvhSettings{});
  const Scene& scene = prepared.scene();
  ThreadPool pool(resolveThreadCount(0));
  const int bounces = scene.frame.tracing.maxBounces;
  std::printf("\n## Light transport: Glint's path tracer and Blender's Cycles (%s, %dx%d, %d samples, %d bounces, "
              "%d threads each)\n\n",
              sceneFile.string().c_str(), size, size, samples, bounces, pool.size());
  if (std::system("command -v blender > /dev/null 2>&1") != 0) {
    std::printf("blender is not installed (make bench-deps installs it): section skipped\n");
    return;
  }
  const fs::path dir = fs::temp_directory_path() / ("glint-bench-cycles-" + std::to_string(getpid()));
  fs::create_directories(dir);
  nlohmann::json text = nlohmann::json::parse(std::ifstream(sceneFile));
  text["image"]["width"] = text["image"]["height"] = size;
  std::ofstream(dir / "scene.json") << text.dump();
  const fs::path script = (fs::absolute(scenes) / "../tests/bench/cycles/glint_scene.py").lexically_normal();
  Runs runs;
  for (int seed = 0; seed < (quick ? 2 : 3); ++seed) {
    runs.glint.push_back(glintFrame(prepared, pool));
    const fs::path out = dir / ("cycles" + std::to_string(seed) + ".exr");
    std::optional<Frame> cycles = cyclesFrame(script, dir / "scene.json", out, samples, bounces, seed);
    if (!cycles) {
      std::printf("blender did not render the scene (run tests/bench/cycles/glint_scene.py by hand to see why)\n");
      fs::remove_all(dir);
      return;
    }
    runs.cycles.push_back(std::move(*cycles));
  }
  printComparison(prepared, runs);
  fs::remove_all(dir);
}

}  // namespace glint::bench
