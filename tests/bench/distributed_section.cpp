#include "tests/bench/distributed_section.h"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "client/farm/distributed_tile_service.h"
#include "client/raster/hybrid_frame.h"
#include "client/raster/offscreen_context.h"
#include "client/raster/raster_scene.h"
#include "common/base/timing.h"
#include "proto/scene_bundle.h"
#include "tests/support/glintd_process.h"
#include "tests/support/dispatch_sim.h"

namespace glint::bench {
namespace {

using server::test::GlintdProcess;

// Records what the tiles of a frame cost: a tile service that passes every
// job to another and keeps each traced tile's time and result size.
class RecordingService : public TileService {
 public:
  explicit RecordingService(TileService& inner) : inner_(inner) {}
  void render(const FrameSettings& frame, std::span<const TileJob> jobs,
              const std::function<void(std::size_t, TileOutput&&)>& done) override {
    inner_.render(frame, jobs, [&](std::size_t i, TileOutput&& out) {
      if (!out.rgb.empty()) tiles.push_back({out.computeMs, out.rgb.size() + kResultOverheadBytes});
      done(i, std::move(out));
    });
  }
  int parallelism() const override { return inner_.parallelism(); }
  void beginFrame() override { inner_.beginFrame(); }

  static constexpr std::size_t kResultOverheadBytes = 96;  // a TileResult's fields and framing
  std::vector<sim::SimTile> tiles;

 private:
  TileService& inner_;
};

struct Room {
  proto::LoadedBundle loaded;
  FrameSettings frame;
};

// Hybrid frames of the room through `service`; their times.
std::vector<HybridTimes> hybridFrames(const Room& room, TileService& service, int frames) {
  gl::OffscreenContext context(room.frame.width, room.frame.height);
  gl::RasterScene raster(context.api(), room.loaded.scene);
  std::vector<HybridTimes> times;
  HybridResult r;
  for (int f = 0; f < frames; ++f) {
    renderHybrid(context.api(), raster, service, room.frame, room.loaded.scene.mask, 64, r);
    times.push_back(r.times);
  }
  return times;
}

// The median frame, the first (shader compilation, scene upload) left out.
double medianFrameMs(const Room& room, TileService& service, int frames) {
  std::vector<HybridTimes> times = hybridFrames(room, service, frames + 1);
  times.erase(times.begin());
  return medianOf(times, &HybridTimes::totalMs);
}

void hostSection(const Room& room, int frames) {
  std::printf("\n## Scene 1 through 1, 2 and 3 glintd on this host (one thread each; median of %d hybrid frames)\n\n",
              frames);
  std::printf("Two cores: this shows what spreading costs, not a speed-up.\n\n");
  std::printf("| tiles traced by | frame ms | vs in process | tiles per server |\n|---|---|---|---|\n");
  const PreparedScene prepared(room.loaded.scene, BvhSettings{});
  ThreadPool pool(1);
  LocalTileService local(prepared, pool);
  const double base = medianFrameMs(room, local, frames);
  std::printf("| in process, 1 thread | %.1f | 1.00x | |\n", base);
  std::vector<std::unique_ptr<GlintdProcess>> servers;
  for (int n = 1; n <= 3; ++n) {
    servers.push_back(std::make_unique<GlintdProcess>(std::vector<std::string>{"--threads", "1"}));
    std::vector<std::string> addresses;
    for (const auto& s : servers) addresses.push_back(s->address());
    DistributedTileService service(resolveServers(addresses), room.loaded.bundle);
    service.awaitServers(std::chrono::seconds(30));
    const double ms = medianFrameMs(room, service, frames);
    std::string shares;
    for (const ServerReport& s : service.lastFrame().servers) shares += (shares.empty() ? "" : " / ") + std::to_string(s.tiles);
    std::printf("| %d glintd | %.1f | %.2fx | %s |\n", n, ms, ms / base, shares.c_str());
  }
}

// One frame after a warm-up frame (the paces learnt, as in view and --frames).
sim::SimResult steadyFrame(const std::vector<sim::SimTile>& tiles, const std::vector<sim::SimServer>& servers,
                           sim::Policy policy, const sim::SimClient& client, const DispatchSettings& settings = {}) {
  std::vector<double> estimates;
  for (const sim::SimTile& t : tiles) estimates.push_back(t.ms);
  std::vector<ServerPace> paces(servers.size());
  std::vector<sim::SimServer> healthy = servers;
  for (sim::SimServer& s : healthy) {
    s.lossAtMs = -1.0;
    s.pauseAtMs = -1.0;
  }
  sim::simulateFrame(tiles, estimates, healthy, policy, settings, paces, client);
  return sim::simulateFrame(tiles, estimates, servers, policy, settings, paces, client);
}

std::vector<sim::SimServer> farm(int n, double bytesPerMs) {
  std::vector<sim::SimServer> servers(static_cast<std::size_t>(n));
  for (sim::SimServer& s : servers) s.bytesPerMs = bytesPerMs;
  return servers;
}

void efficiencyTable(const std::vector<sim::SimTile>& tiles) {
  std::printf("\n### Parallel efficiency (ideal / simulated frame; 0.2 ms round trip; every result also crosses the "
              "client's link)\n\n");
  std::printf("| servers | static round robin, 1 Gbit | this scheduler, 1 Gbit | static round robin, 10 Gbit | "
              "this scheduler, 10 Gbit |\n|---|---|---|---|---|\n");
  for (int n : {1, 2, 4, 8, 16, 32, 64}) {
    std::printf("| %d |", n);
    for (double rate : {125000.0, 1250000.0}) {
      const auto servers = farm(n, rate);
      const sim::SimClient client{rate};
      const double ideal = sim::idealMs(tiles, servers, client);
      for (sim::Policy p : {sim::Policy::kStaticRoundRobin, sim::Policy::kDispatcher}) {
        std::printf(" %.0f %% |", 100.0 * ideal / steadyFrame(tiles, servers, p, client).frameMs);
      }
    }
    std::printf("\n");
  }
}

void slowAndLostTable(const std::vector<sim::SimTile>& tiles) {
  const sim::SimClient client{125000.0};
  std::printf("\n### One server 4x slow, one lost half-way (1 Gbit; frame / ideal of the servers that work)\n\n");
  std::printf("| servers | 4x slow: round robin | 4x slow: this scheduler | lost (closes): this scheduler | "
              "lost (stalls, 2 s timeout): extra ms | bound: 2000 ms + its outstanding tiles |\n|---|---|---|---|---|---|\n");
  for (int n : {4, 16}) {
    auto slow = farm(n, client.bytesPerMs);
    slow.back().speed = 0.25;
    const double slowIdeal = sim::idealMs(tiles, slow, client);
    const double rr = steadyFrame(tiles, slow, sim::Policy::kStaticRoundRobin, client).frameMs / slowIdeal;
    const double ours = steadyFrame(tiles, slow, sim::Policy::kDispatcher, client).frameMs / slowIdeal;
    const auto healthy = farm(n, client.bytesPerMs);
    const double healthyMs = steadyFrame(tiles, healthy, sim::Policy::kDispatcher, client).frameMs;
    auto closes = healthy;
    closes.back().lossAtMs = healthyMs / 2;
    auto stalls = closes;
    stalls.back().silentLoss = true;
    std::vector<sim::SimServer> survivors(healthy.begin(), healthy.end() - 1);
    const double survivorIdeal = sim::idealMs(tiles, survivors, client);
    const double closed = steadyFrame(tiles, closes, sim::Policy::kDispatcher, client).frameMs / survivorIdeal;
    const double stalledExtra = steadyFrame(tiles, stalls, sim::Policy::kDispatcher, client).frameMs - healthyMs;
    // Its outstanding tiles: at most its window, about two of the costliest tiles.
    double costliest = 0.0;
    for (const sim::SimTile& t : tiles) costliest = std::max(costliest, t.ms);
    std::printf("| %d | %.2fx | %.2fx | %.2fx | %.0f | %.0f |\n", n, rr, ours, closed, stalledExtra,
                2000.0 + 2.0 * costliest);
  }
}

double busyMs(const sim::SimResult& r) {
  double sum = 0.0;
  for (const double ms : r.busyMs) sum += ms;
  return sum;
}

// "97 ms / 1.05x, 3 % copied, 1 % wasted": a frame with and without
// hedging, against `reference`.
std::string hedgedCell(const std::vector<sim::SimTile>& tiles, const std::vector<sim::SimServer>& servers,
                       const sim::SimClient& client, double reference, bool extra) {
  std::string cell;
  for (const bool hedge : {true, false}) {
    const sim::SimResult r = steadyFrame(tiles, servers, sim::Policy::kDispatcher, client, {.hedge = hedge});
    char text[96];
    if (extra) {
      std::snprintf(text, sizeof text, "%+.0f ms", r.frameMs - reference);
    } else {
      std::snprintf(text, sizeof text, "%.2fx", r.frameMs / reference);
    }
    cell += text;
    if (hedge) {
      std::snprintf(text, sizeof text, " (%.1f %% hedged, %.1f %% copied in all, %.1f %% wasted) / ",
                    100.0 * static_cast<double>(r.hedged) / static_cast<double>(tiles.size()),
                    100.0 * static_cast<double>(r.duplicated) / static_cast<double>(tiles.size()),
                    100.0 * r.wastedMs / busyMs(r));
      cell += text;
    }
  }
  return cell;
}

// What a user sees: the client's own GL pass (raster, read-back, compose)
// is the serial part of every frame, however many servers trace; and a
// straggler, hedged and not.
void userEfficiencyTable(const std::vector<sim::SimTile>& tiles, double glMs) {
  const sim::SimClient client{125000.0};
  std::printf("\n### As a user sees it: the frame with the client's GL pass (%.1f ms, measured here), and stragglers "
              "(1 Gbit)\n\n", glMs);
  std::printf("Efficiency = speed-up over one server / servers. Stragglers: the frame with hedging (copies "
              "hedged past the p95, copies in all with the last bucket's, thread time spent on copies that came "
              "second) / without hedging.\n\n");
  std::printf("| servers | frame ms | efficiency, traced part | efficiency, whole frame | one 4x slow: frame / ideal | "
              "one stopped 2 s a quarter in: ms over the healthy frame | two stopped so: ms over the healthy frame |\n"
              "|---|---|---|---|---|---|---|\n");
  const double oneMs = glMs + steadyFrame(tiles, farm(1, client.bytesPerMs), sim::Policy::kDispatcher, client).frameMs;
  for (int n : {4, 8, 16}) {
    const auto healthy = farm(n, client.bytesPerMs);
    const double tracedMs = steadyFrame(tiles, healthy, sim::Policy::kDispatcher, client).frameMs;
    auto slow = healthy;
    slow.back().speed = 0.25;
    auto stopped = healthy;
    stopped.back().pauseAtMs = tracedMs / 4;
    stopped.back().pauseForMs = 2000.0;
    auto twoStopped = stopped;
    twoStopped.front().pauseAtMs = tracedMs / 4;
    twoStopped.front().pauseForMs = 2000.0;
    std::printf("| %d | %.1f | %.0f %% | %.0f %% | %s | %s | %s |\n", n, glMs + tracedMs,
                100.0 * sim::idealMs(tiles, healthy, client) / tracedMs, 100.0 * oneMs / (n * (glMs + tracedMs)),
                hedgedCell(tiles, slow, client, sim::idealMs(tiles, slow, client), false).c_str(),
                hedgedCell(tiles, stopped, client, tracedMs, true).c_str(),
                hedgedCell(tiles, twoStopped, client, tracedMs, true).c_str());
  }
}

void simulationSection(const std::string& scenes, bool quick) {
  Room room{proto::loadSceneBundle(std::filesystem::path(scenes) / "room.json"), {}};
  room.frame = room.loaded.scene.frame;
  room.frame.width = quick ? 480 : 1920;
  room.frame.height = quick ? 270 : 1080;
  const PreparedScene prepared(room.loaded.scene, BvhSettings{});
  ThreadPool pool(1);
  LocalTileService local(prepared, pool);
  RecordingService recording(local);
  hybridFrames(room, recording, 1);
  std::vector<HybridTimes> times = hybridFrames(room, local, quick ? 2 : 6);
  times.erase(times.begin());  // shader compilation
  double total = 0.0;
  for (const sim::SimTile& t : recording.tiles) total += t.ms;
  std::printf("\n## The scheduler simulated: scene 1's hybrid frame at %dx%d (%zu traced 64-pixel tiles, %.0f ms on one "
              "thread, measured here)\n",
              room.frame.width, room.frame.height, recording.tiles.size(), total);
  std::printf("\nEach server is one thread at this machine's speed. Frames after a warm-up frame (paces learnt).\n");
  efficiencyTable(recording.tiles);
  slowAndLostTable(recording.tiles);
  std::vector<double> glMs;
  for (const HybridTimes& t : times) glMs.push_back(t.totalMs - t.traceMs);
  userEfficiencyTable(recording.tiles, median(glMs));
}

}  // namespace

void distributedSection(const std::string& scenes, bool quick) {
  Room room{proto::loadSceneBundle(std::filesystem::path(scenes) / "room.json"), {}};
  room.frame = room.loaded.scene.frame;
  if (quick) {
    room.frame.width = 160;
    room.frame.height = 120;
  }
  hostSection(room, quick ? 2 : 21);
  simulationSection(scenes, quick);
}

}  // namespace glint::bench
