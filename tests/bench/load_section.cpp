#include "tests/bench/load_section.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <vector>

#include "client/farm/distributed_tile_service.h"
#include "common/base/error.h"
#include "common/render/frame.h"
#include "common/base/thread_pool.h"
#include "common/base/timing.h"
#include "proto/scene_bundle.h"
#include "tests/support/glintd_process.h"

namespace glint::bench {
namespace {

struct ClientLoad {
  std::vector<double> latencyMs;  // one per frame that came back right
  int errors = 0;                 // frames that failed or differed from the in-process image
};

// One client: connects, then renders frames until the deadline; reconnects
// after an error.
ClientLoad runClient(const std::string& address, const proto::SceneBundle& bundle, const FrameSettings& frame,
                     const FrameImage& expected, Clock::time_point deadline) {
  ClientLoad load;
  while (Clock::now() < deadline) {
    try {
      DistributedTileService service(resolveServers({address}), bundle);
      while (Clock::now() < deadline) {
        const auto start = Clock::now();
        const FrameImage image = renderFrame(service, frame, {}).image;
        if (image.rgb != expected.rgb) {
          ++load.errors;
        } else {
          load.latencyMs.push_back(msSince(start));
        }
      }
    } catch (const InputError&) {
      ++load.errors;
    }
  }
  return load;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

}  // namespace

void loadSection(const std::string& scenes, bool quick) {
  const int clients = quick ? 4 : 16;
  const int seconds = quick ? 2 : 60;
  const proto::LoadedBundle room = proto::loadSceneBundle(std::filesystem::path(scenes) / "room.json");
  FrameSettings frame = room.scene.frame;
  frame.width = 160;
  frame.height = 120;
  FrameImage expected;
  {
    const PreparedScene prepared(room.scene, BvhSettings{});
    ThreadPool pool(1);
    LocalTileService local(prepared, pool);
    expected = renderFrame(local, frame, {}).image;
  }
  server::test::GlintdProcess glintd({"--threads", "2"});
  const long startKb = glintd.residentKb();
  const int startDescriptors = glintd.openDescriptors();
  const auto deadline = Clock::now() + std::chrono::seconds(seconds);
  std::vector<ClientLoad> loads(static_cast<std::size_t>(clients));
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < loads.size(); ++i) {
    threads.emplace_back([&, i] { loads[i] = runClient(glintd.address(), room.bundle, frame, expected, deadline); });
  }
  for (std::thread& t : threads) t.join();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // connections closing
  std::vector<double> latency;
  int errors = 0;
  for (const ClientLoad& l : loads) {
    latency.insert(latency.end(), l.latencyMs.begin(), l.latencyMs.end());
    errors += l.errors;
  }
  std::printf("\n## Load: %d clients rendering the room at %dx%d through one glintd (2 threads) for %d s\n\n",
              clients, frame.width, frame.height, seconds);
  std::printf("| frames | errors | latency median ms | latency p99 ms | server RSS start / peak / end MB | "
              "open descriptors start / end |\n|---|---|---|---|---|---|\n");
  std::printf("| %zu | %d | %.1f | %.1f | %.1f / %.1f / %.1f | %d / %d |\n", latency.size(), errors,
              percentile(latency, 0.5), percentile(latency, 0.99), startKb / 1024.0, glintd.peakResidentKb() / 1024.0,
              glintd.residentKb() / 1024.0, startDescriptors, glintd.openDescriptors());
}

}  // namespace glint::bench
