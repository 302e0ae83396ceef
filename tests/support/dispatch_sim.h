#pragma once

#include <cstddef>
#include <vector>

#include "client/farm/tile_dispatcher.h"

namespace glint::sim {

// A server in virtual time: threads tracing tiles in the order they arrive,
// a link of some rate and round trip, and possibly a moment it is lost.
struct SimServer {
  int threads = 1;
  double speed = 1.0;           // tiles take ms / speed
  double rttMs = 0.2;
  double bytesPerMs = 125000;   // 1 Gbit/s
  double lossAtMs = -1.0;       // < 0: never lost
  bool silentLoss = false;      // lost as SIGSTOP (stalls) rather than as SIGKILL (closes)
  double joinAtMs = 0.0;        // when its scene is ready; < 0: not in the farm this frame
  double pauseAtMs = -1.0;      // stopped (SIGSTOP) at this moment, < 0: never ...
  double pauseForMs = 0.0;      // ... and continued (SIGCONT) this much later
};

struct SimTile {
  double ms = 1.0;               // tracing time at speed 1
  std::size_t resultBytes = 0;   // the TileResult message
};

enum class Policy {
  kDispatcher,        // client/farm/tile_dispatcher
  kStaticRoundRobin,  // tile i to server i mod n, all at once (OSPRay's default)
};

struct SimResult {
  bool completed = false;        // every tile delivered
  double frameMs = 0.0;
  std::vector<int> firstDeliveries;  // per tile: results the frame took (must be 1)
  std::size_t reissued = 0;
  std::size_t duplicated = 0;
  std::size_t hedged = 0;
  double wastedMs = 0.0;             // thread time spent on copies whose result came second
  std::size_t cancelledQueued = 0;   // copies a Cancel removed before they ran
  std::vector<double> busyMs;        // per server: thread time spent tracing
};

// The client's own link, which every result crosses (0: unlimited).
struct SimClient {
  double bytesPerMs = 0.0;
};

// One frame in virtual time. `estimates` are the costs the dispatcher is
// given (tile ms, or a model of them); `paces` carry over between frames.
SimResult simulateFrame(const std::vector<SimTile>& tiles, const std::vector<double>& estimates,
                        const std::vector<SimServer>& servers, Policy policy, const DispatchSettings& settings,
                        std::vector<ServerPace>& paces, const SimClient& client = {});

// Frame time if the work were shared perfectly: total tile time over the
// servers' combined speed, or the client's link time for every result
// where that is longer.
double idealMs(const std::vector<SimTile>& tiles, const std::vector<SimServer>& servers, const SimClient& client = {});

}  // namespace glint::sim
