// glint-bench: prints what the ray-tracing core costs. Numbers, never
// assertions: medians over repeated runs, and ratios against peers measured
// in the same run (QSplit vs SAH, POV-Ray 3.7 vs Glint).
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/geometry/bvh.h"
#include "common/base/error.h"
#include "common/render/frame.h"
#include "common/base/heap_tuning.h"
#include "client/raster/hybrid_frame.h"
#include "client/raster/offscreen_context.h"
#include "client/raster/raster_scene.h"
#include "client/farm/distributed_tile_service.h"
#include "common/scene/scene_load.h"
#include "common/base/timing.h"
#include "tests/bench/bench_timing.h"
#include "proto/scene_bundle.h"
#include "server/log.h"
#include "tests/support/background_server.h"
#include "tests/bench/bench_scenes.h"
#include "tests/bench/distributed_section.h"
#include "tests/bench/embree_section.h"
#include "tests/bench/load_section.h"
#include "tests/bench/gl_backend_section.h"
#include "tests/bench/mesh_file_section.h"
#include "tests/bench/perceptual_section.h"
#include "tests/bench/povray_run.h"
#include "tests/bench/soft_shadow_section.h"
#include "tests/bench/indirect_section.h"
#include "tests/bench/transport_section.h"

namespace glint::bench {

// The sections, in the order they run (all by default).
constexpr std::array<const char*, 14> kSections{"bvh",  "room", "accuracy",    "protocol", "hybrid",    "perceptual", "soft",
                                                "gl",   "load", "distributed", "meshfile", "embree", "transport", "indirect"};

namespace {

struct Options {
  std::string scenes = "scenes";
  bool quick = false;
  bool povray = true;
  int runs = 7;
  int tileSize = 64;
  std::vector<std::string> sections{kSections.begin(), kSections.end()};
  bool wants(const std::string& s) const { return std::find(sections.begin(), sections.end(), s) != sections.end(); }
};

// The machine the numbers come from: the CPU's name (Linux's
// /proc/cpuinfo), its hardware threads and the box test this CPU gets
// (tables from different hosts are not comparable; docs/performance.md).
std::string hostLine() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string cpu = "CPU unknown";
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) != 0 || line.find(':') == std::string::npos) continue;
    cpu = line.substr(line.find_first_not_of(" \t", line.find(':') + 1));
    break;
  }
  const bool eight = fastestBoxTestWidth() == BoxTestWidth::kEight;
  return "host: " + cpu + ", " + std::to_string(std::max(1u, std::thread::hardware_concurrency())) +
         " hardware threads; box test: " + (eight ? "eight lanes (AVX2)" : "four lanes");
}

struct BvhResult {
  double buildOneMs;  // the build on one thread
  double buildMs;     // on every hardware thread
  double closestMrays;
  double anyMrays;
};

BvhResult measureBvh(const Geometry& g, const std::vector<Ray>& rays, BvhBuilder builder, int runs) {
  BvhSettings settings;
  settings.builder = builder;
  settings.buildThreads = 1;
  Bvh bvh;
  const double buildOneMs = medianMs(runs, [&] { bvh = Bvh::build(g, settings); });
  settings.buildThreads = 0;  // every hardware thread
  const double buildMs = medianMs(runs, [&] { bvh = Bvh::build(g, settings); });
  std::size_t sink = 0;
  const double closestMs = medianMs(runs, [&] {
    for (const Ray& r : rays) sink += bvh.intersect(r, 1e30f) ? 1 : 0;
  });
  const double anyMs = medianMs(runs, [&] {
    for (const Ray& r : rays) sink += bvh.occluded(r, 1e30f) ? 1 : 0;
  });
  if (sink == 42) std::puts("");  // keeps the loops from being optimised away
  const double n = static_cast<double>(rays.size());
  return {buildOneMs, buildMs, n / closestMs / 1e3, n / anyMs / 1e3};
}

void bvhSection(const Options& o, const Scene& room) {
  std::printf("\n## BVH: build (1 thread and %u), traversal on 1 thread (median of %d)\n\n",
              std::max(1u, std::thread::hardware_concurrency()), o.runs);
  std::printf("| scene | builder | primitives | build ms, 1 thread | build ms, all | closest hit Mrays/s | any hit Mrays/s |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  const int w = o.quick ? 100 : 1000;
  const int d = o.quick ? 50 : 500;
  const Geometry terrainGeometry = terrain(w, d);
  struct Case {
    const char* name;
    const Geometry* g;
    std::vector<Ray> rays;
  };
  const int rayCount = o.quick ? 10'000 : 1'000'000;
  const Case cases[] = {{"room", &room.geometry, roomRays(rayCount, 1)},
                        {"terrain", &terrainGeometry, terrainRays(rayCount, 2)}};
  for (const Case& c : cases) {
    BvhResult r[2];
    const BvhBuilder builders[2] = {BvhBuilder::kQSplit, BvhBuilder::kSah};
    for (int b = 0; b < 2; ++b) {
      r[b] = measureBvh(*c.g, c.rays, builders[b], o.runs);
      std::printf("| %s | %s | %u | %.2f | %.2f | %.2f | %.2f |\n", c.name, std::string(enumWord(builders[b])).c_str(),
                  c.g->primitiveCount(), r[b].buildOneMs, r[b].buildMs, r[b].closestMrays, r[b].anyMrays);
    }
    std::printf("| %s | sah / qsplit | | | | **%.2fx** | %.2fx |\n", c.name, r[1].closestMrays / r[0].closestMrays,
                r[1].anyMrays / r[0].anyMrays);
  }
}

double renderMs(const Scene& scene, ThreadPool& pool, int runs, RayStats* stats = nullptr) {
  const PreparedScene prepared(scene, BvhSettings{});
  const Renderer renderer(prepared, scene.frame);
  FrameResult result;
  const double ms = medianMs(runs, [&] { result = renderFrame(renderer, pool, {}); });
  if (stats) *stats = result.stats;
  return ms;
}

// POV-Ray 3.7 rendering the same room at the same size with 4 jittered
// samples per pixel (+A0.0: supersample every pixel; +AM1 +R2: 2 x 2 grid;
// +J: jitter). Medians of `runs`; negative when POV-Ray is not installed or
// fails.
struct PovrayTimes {
  double processMs = -1.0;
  double traceMs = -1.0;
};

PovrayTimes povrayTimes(const Options& o, int width, int height, int runs) {
  if (!povrayInstalled()) return {};
  const std::filesystem::path pov = std::filesystem::path(o.scenes) / "room.pov";
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "glint-bench-povray.png";
  std::vector<double> process, trace;
  for (int i = 0; i < runs; ++i) {
    const PovrayRun run = runPovray(pov, out, width, height, "+A0.0 +AM1 +R2 +J1.0");
    process.push_back(run.processMs);
    trace.push_back(run.renderMs);
  }
  std::filesystem::remove(out);
  if (*std::min_element(trace.begin(), trace.end()) <= 0.0) return {};
  return {median(process), median(trace)};
}

void roomSection(const Options& o, const Scene& room, ThreadPool& pool) {
  std::printf("\n## The room, %dx%d, 4 jittered samples, tent filter, full trace, %d threads\n\n", room.frame.width,
              room.frame.height, pool.size());
  RayStats stats;
  const double glint = renderMs(room, pool, o.runs, &stats);
  std::printf("| renderer | median ms | rays |\n|---|---|---|\n");
  std::printf("| glint | %.1f | %.2f M |\n", glint, static_cast<double>(stats.total()) / 1e6);
  const PovrayTimes pov = o.povray ? povrayTimes(o, room.frame.width, room.frame.height, o.quick ? 1 : 5) : PovrayTimes{};
  if (pov.traceMs > 0.0) {
    std::printf("| povray 3.7 (same room, scenes/room.pov), its Trace Time | %.1f | |\n", pov.traceMs);
    std::printf("| povray 3.7, the whole process (start-up, parse, PNG) | %.1f | |\n", pov.processMs);
    std::printf("\nPOV-Ray's Trace Time / Glint: **%.2fx** (its whole process / Glint: %.2fx)\n", pov.traceMs / glint,
                pov.processMs / glint);
  } else {
    std::printf("\nPOV-Ray not measured (not installed, or --no-povray; `make bench-deps` installs it).\n");
  }
}

// What accuracy costs: each setting of the room varied on its own.
void accuracySection(const Options& o, const Scene& room, ThreadPool& pool) {
  std::printf("\n## What accuracy costs (the room, %dx%d, %d threads, median of %d)\n\n", room.frame.width,
              room.frame.height, pool.size(), o.runs);
  struct Row {
    std::string name;
    double ms;
    RayStats stats;
  };
  std::vector<Row> rows;
  const auto row = [&](const std::string& name, const std::function<void(Scene&)>& edit) {
    Scene s = room;
    edit(s);
    Row r{name, 0.0, {}};
    r.ms = renderMs(s, pool, o.runs, &r.stats);
    rows.push_back(r);
  };
  row("1 sample, regular, box", [](Scene& s) {
    s.frame.sampling = {SamplePattern::kRegular, 1, FilterType::kBox, 0};
  });
  for (int n : {4, 9, 16}) {
    row(std::to_string(n) + " samples, jittered, tent" + (n == 4 ? " (the thesis's)" : ""),
        [n](Scene& s) { s.frame.sampling.samples = n; });
  }
  for (FilterType f : {FilterType::kBox, FilterType::kGaussian, FilterType::kMitchell}) {
    row("4 samples, jittered, " + std::string(enumWord(f)), [f](Scene& s) { s.frame.sampling.filter = f; });
  }
  for (int depth : {1, 2, 3, 8}) {
    row("max_depth " + std::to_string(depth), [depth](Scene& s) { s.frame.tracing.maxDepth = depth; });
  }
  for (float w : {0.5f, 0.1f, 0.001f, 0.0f}) {
    char name[64];
    std::snprintf(name, sizeof name, "min_weight %g", static_cast<double>(w));
    row(name, [w](Scene& s) { s.frame.tracing.minWeight = w; });
  }
  const double base = rows[1].ms;  // 4 jittered samples, tent: the thesis's setting
  std::printf("| setting | trace ms | rays | vs. the thesis's setting |\n|---|---|---|---|\n");
  for (const Row& r : rows) {
    std::printf("| %s | %.1f | %.2f M | %.2fx |\n", r.name.c_str(), r.ms,
                static_cast<double>(r.stats.total()) / 1e6, r.ms / base);
  }
  std::printf("\nEach row changes one setting of the room (4 jittered samples, tent, max_depth 5,\n"
              "min_weight 0.01); rays counts every primary, shadow, reflected and refracted ray.\n");
}

// A quiet glintd on a free loopback port with 2 tracing threads, as the
// in-process side has.
server::ServerOptions loopbackServer() {
  server::setLogging(false);
  server::ServerOptions o;
  o.listen = "127.0.0.1:0";
  o.threads = 2;
  o.handleSignals = false;
  return o;
}

// Certificates for the TLS rows, made by deploy/glint-certs in a temporary
// folder (removed with the object).
struct BenchCertificates {
  explicit BenchCertificates(const std::string& scenes)
      : dir(std::filesystem::temp_directory_path() / ("glint-bench-tls-" + std::to_string(::getpid()))) {
    const std::string certs = (std::filesystem::path(scenes) / ".." / "deploy" / "glint-certs").string();
    const std::string d = dir.string();
    const std::string command = certs + " " + d + " ca && " + certs + " " + d + " server glintd 127.0.0.1 && " +
                                certs + " " + d + " client bench";
    if (std::system((command + " > /dev/null").c_str()) != 0) throw InputError("cannot make certificates: " + command);
  }
  ~BenchCertificates() { std::filesystem::remove_all(dir); }
  std::string file(const char* name) const { return (dir / name).string(); }
  std::filesystem::path dir;
};

// The cost of going through glintd: the same frames in process, through a
// server on loopback (in this process, its own 2 threads) over TCP, and
// through another over TLS 1.3; medians of 20+.
void protocolSection(const Options& o, const Scene& room) {
  const int frames = o.quick ? 2 : 21;
  const proto::LoadedBundle loaded = proto::loadSceneBundle(std::filesystem::path(o.scenes) / "room.json");
  const BenchCertificates certs(o.scenes);
  server::BackgroundServer glintd(loopbackServer());
  server::ServerOptions tlsOptions = loopbackServer();
  tlsOptions.tls = {certs.file("ca.pem"), certs.file("glintd.pem"), certs.file("glintd.key")};
  server::BackgroundServer glintdTls(tlsOptions);
  DistributedSettings tlsClient;
  tlsClient.tls = {certs.file("ca.pem"), certs.file("bench.pem"), certs.file("bench.key")};
  std::printf("\n## Through glintd on loopback vs in process (2 threads each, %d-pixel tiles, %d frames)\n\n",
              o.tileSize, frames);
  std::printf("| frame | in process ms | through glintd ms | overhead ms (median of pairs) | over TLS 1.3 ms | TLS "
              "over TCP ms (median of pairs) | bytes received | masked pixels x 3 | bytes sent |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  // The room as the thesis renders it, and the same view of an empty scene,
  // where tracing costs almost nothing and the difference is the protocol.
  Scene empty = room;
  empty.geometry = Geometry{};
  empty.lights.clear();
  proto::SceneBundle emptyBundle = loaded.bundle;
  emptyBundle.text = R"({"glint": 1, "image": {"width": 640, "height": 480},
    "camera": {"eye": [0.3, 1.6, 5.2], "look_at": [0, 1.2, 0], "fov_y": 50}, "objects": []})";
  emptyBundle.files.clear();
  struct Case {
    const char* name;
    const Scene* scene;
    const proto::SceneBundle* bundle;
  };
  ThreadPool pool(2);
  for (const Case& c : {Case{"the room", &room, &loaded.bundle}, Case{"empty scene (protocol only)", &empty, &emptyBundle}}) {
    const PreparedScene prepared(*c.scene, BvhSettings{});
    LocalTileService local(prepared, pool);
    DistributedTileService remote(resolveServers({glintd.address()}), *c.bundle);
    DistributedTileService secure(resolveServers({glintdTls.address()}), *c.bundle, tlsClient);
    const FrameSettings frame = c.scene->frame;
    // Frames alternate between the paths and each overhead is the median of
    // the pairs' differences: slow drifts of the machine cancel out.
    std::vector<double> localTimes, remoteTimes, tlsTimes, differences, tlsDifferences;
    FrameOptions frameOptions;
    frameOptions.tileSize = o.tileSize;
    double received = 0.0, sent = 0.0;
    for (int i = 0; i < frames; ++i) {
      localTimes.push_back(medianMs(1, [&] { renderFrame(local, frame, frameOptions); }));
      remoteTimes.push_back(medianMs(1, [&] { renderFrame(remote, frame, frameOptions); }));
      tlsTimes.push_back(medianMs(1, [&] { renderFrame(secure, frame, frameOptions); }));
      differences.push_back(remoteTimes.back() - localTimes.back());
      tlsDifferences.push_back(tlsTimes.back() - remoteTimes.back());
      received += static_cast<double>(remote.lastFrame().servers[0].bytesIn) / frames;
      sent += static_cast<double>(remote.lastFrame().servers[0].bytesOut) / frames;
    }
    std::printf("| %s | %.1f | %.1f | %.2f | %.1f | %.2f | %.0f | %d | %.0f |\n", c.name, median(localTimes),
                median(remoteTimes), median(differences), median(tlsTimes), median(tlsDifferences), received,
                frame.width * frame.height * 3, sent);
  }
}

// One scene's hybrid frames through one tile service, each beside the
// same frame traced in full (--mask all) by the same service, alternating
// so that both see the same stretch of the machine; `between` runs before
// every pair (POV-Ray's runs for scene 1).
struct HybridRow {
  std::vector<HybridTimes> times;
  std::vector<double> glPass;  // raster + readback + compose, per frame
  std::vector<double> full;
  HybridResult last;
};

HybridRow hybridRow(gl::RasterScene& raster, const gl::OffscreenContext& context, TileService& service,
                    const FrameSettings& frame, const MaskSettings& mask, int frames,
                    const std::function<void(int)>& between) {
  HybridRow row;
  FrameOptions full;
  full.tileSize = 64;
  for (int f = 0; f < frames + 1; ++f) {
    between(f);
    renderHybrid(context.api(), raster, service, frame, mask, 64, row.last);
    const double fullMs = medianMs(1, [&] { renderFrame(service, frame, full); });
    if (f == 0) continue;  // the first frame compiles the shaders
    row.times.push_back(row.last.times);
    row.glPass.push_back(row.last.times.rasterMs + row.last.times.readbackMs + row.last.times.composeMs);
    row.full.push_back(fullMs);
  }
  return row;
}

// The thesis's Table 4.1 with Glint's hybrid frame: each step's median over
// the frames, in process and (scenes 1 and 2) through glintd, beside the
// same scene's full trace and POV-Ray's full trace of the room, all
// measured in the same run.
void hybridSection(const Options& o) {
  const int frames = o.quick ? 2 : 21;
  server::BackgroundServer glintd(loopbackServer());
  const std::string address = glintd.address();
  std::printf("\n## The hybrid frame: the thesis's Table 4.1 (median of %d frames, 2 tracing threads)\n\n", frames);
  std::printf("GL pass = raster + readback + compose; traced = masked pixels (of them, raster edges); full = the "
              "same frame traced in full (--mask all) by the same service, alternating with the hybrid frames.\n\n");
  std::printf("| scene | tiles from | raster ms | readback ms | compose ms | **GL pass ms** | traced (edges) | RT unit ms "
              "| frame ms | full trace ms | **frame / full** | thesis RT unit / frame ms |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const char* const scenes[4] = {"room.json", "room-gl-floor.json", "glass.json", "bunny.json"};
  const char* const thesis[4] = {"2046 / 2068", "878 / 902", "", ""};
  double sceneOneFrame = 0.0;
  std::vector<double> povTimes, povProcessTimes;
  for (int index = 0; index < 4; ++index) {
    proto::LoadedBundle loaded = proto::loadSceneBundle(std::filesystem::path(o.scenes) / scenes[index]);
    FrameSettings frame = loaded.scene.frame;
    if (o.quick) {
      frame.width = 160;
      frame.height = 120;
    }
    const PreparedScene prepared(loaded.scene, BvhSettings{});
    ThreadPool pool(2);
    LocalTileService local(prepared, pool);
    std::optional<DistributedTileService> remote;
    if (index < 2) remote.emplace(resolveServers({address}), loaded.bundle);
    gl::OffscreenContext context(frame.width, frame.height);
    gl::RasterScene raster(context.api(), prepared.scene());
    std::vector<TileService*> services{&local};
    if (remote) services.push_back(&*remote);
    for (TileService* service : services) {
      const bool inProcess = service == &local;
      const auto between = [&](int f) {
        if (!o.povray || o.quick || index != 0 || !inProcess || f % 4 != 0) return;
        const PovrayTimes pov = povrayTimes(o, 640, 480, 1);
        if (pov.traceMs <= 0.0) return;
        povTimes.push_back(pov.traceMs);
        povProcessTimes.push_back(pov.processMs);
      };
      HybridRow row = hybridRow(raster, context, *service, frame, prepared.scene().mask, frames, between);
      const auto step = [&row](double HybridTimes::*s) { return medianOf(row.times, s); };
      const double frameMs = step(&HybridTimes::totalMs), fullMs = median(row.full);
      std::printf("| %d (%s) | %s | %.1f | %.1f | %.1f | **%.1f** | %zu (%zu) | %.1f | %.1f | %.1f | **%.2f** | %s |\n",
                  index + 1, scenes[index], inProcess ? "in process" : "glintd", step(&HybridTimes::rasterMs),
                  step(&HybridTimes::readbackMs), step(&HybridTimes::composeMs), median(row.glPass),
                  row.last.maskedPixels, row.last.rasterEdgePixels, step(&HybridTimes::traceMs), frameMs, fullMs,
                  frameMs / fullMs, thesis[index]);
      if (index == 0 && inProcess) sceneOneFrame = frameMs;
    }
  }
  if (!povTimes.empty()) {
    const double pov = median(povTimes);
    std::printf("\nPOV-Ray 3.7 full trace of the room (median of %zu runs between scene 1's frames): its Trace Time "
                "%.1f ms, scene 1's hybrid frame is **%.2fx** faster; its whole process %.1f ms (%.2fx).\n",
                povTimes.size(), pov, pov / sceneOneFrame, median(povProcessTimes),
                median(povProcessTimes) / sceneOneFrame);
  }
}

}  // namespace
}  // namespace glint::bench

int main(int argc, char** argv) {
  using namespace glint;
  keepFreedMemoryForReuse();  // as glint and glintd do
  bench::Options o;
  CLI::App app{"glint-bench: timings of the ray-tracing core (medians; prints, never asserts)"};
  app.add_option("--scenes", o.scenes, "Folder with room.json and room.pov")->check(CLI::ExistingDirectory);
  app.add_flag("--quick", o.quick, "Small sizes and one run: a smoke test, not a measurement");
  app.add_option("--runs", o.runs, "Runs per measurement (the median is printed)")->check(CLI::Range(1, 101));
  bool noPovray = false;
  app.add_flag("--no-povray", noPovray, "Skip the POV-Ray comparison");
  app.add_option("--tile-size", o.tileSize, "Tile edge for the glintd comparison")->check(CLI::Range(8, 1024));
  std::string sectionList;
  for (const char* s : bench::kSections) sectionList += (sectionList.empty() ? "" : ", ") + std::string(s);
  app.add_option("--sections", o.sections, "Sections to run: " + sectionList + " (default: all)")
      ->delimiter(',')
      ->check(CLI::IsMember(std::vector<std::string>(bench::kSections.begin(), bench::kSections.end())));
  CLI11_PARSE(app, argc, argv);
  o.povray = !noPovray;
  if (o.quick) o.runs = 1;
  try {
    Scene room = loadSceneFile(std::filesystem::path(o.scenes) / "room.json");
    if (o.quick) {
      room.frame.width = 160;
      room.frame.height = 120;
    }
    ThreadPool pool(2);
    std::printf("# glint-bench%s\n\n%s\n", o.quick ? " (quick: not a measurement)" : "", bench::hostLine().c_str());
    if (o.wants("bvh")) bench::bvhSection(o, room);
    if (o.wants("room")) bench::roomSection(o, room, pool);
    if (o.wants("accuracy")) bench::accuracySection(o, room, pool);
    if (o.wants("protocol")) bench::protocolSection(o, room);
    if (o.wants("hybrid")) bench::hybridSection(o);
    if (o.wants("perceptual")) bench::perceptualSection(o.scenes, o.quick);
    if (o.wants("soft")) bench::softShadowSection(o.scenes, o.quick);
    if (o.wants("gl")) bench::glBackendSection(o.scenes, o.quick);
    if (o.wants("load")) bench::loadSection(o.scenes, o.quick);
    if (o.wants("distributed")) bench::distributedSection(o.scenes, o.quick);
    if (o.wants("meshfile")) bench::meshFileSection(o.quick, o.runs);
    if (o.wants("embree")) bench::embreeSection(o.scenes, o.quick, o.runs);
    if (o.wants("transport")) bench::transportSection(o.scenes, o.quick);
    if (o.wants("indirect")) bench::indirectSection(o.scenes, o.quick, o.povray);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint-bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
