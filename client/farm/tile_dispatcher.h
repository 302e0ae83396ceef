#pragma once

#include <cstddef>
#include <deque>
#include <set>
#include <vector>

namespace glint {

// What the client has learnt about one server's pace, kept from frame to
// frame. Cost is in the dispatcher's cost units (see TileDispatcher).
struct ServerPace {
  int threads = 1;
  double costPerMs = 0.0;  // measured throughput, all threads; 0 until the first frame it served
  double rttMs = -1.0;     // smallest seen (latency - compute) of a tile; < 0 unknown
};

// When a server counts as stalled, how far ahead of it to keep work, and
// when a straggling tile is copied.
struct DispatchSettings {
  double stallTimeoutMs = 2000.0;  // tiles outstanding, nothing delivered for this long: lost
  double leadMs = 10.0;            // work queued beyond one round trip (chosen in docs/distributed.md)
  int initialTilesPerThread = 2;   // window before the server's pace is known
  // Hedging ("The Tail at Scale", Dean and Barroso, CACM 2013): a tile
  // outstanding longer than this percentile of the frame's tile latencies
  // so far (sent to delivered), and at least hedgeMinMs, is copied to the
  // least loaded server that is not straggling itself; after
  // hedgeMinSamples results.
  bool hedge = true;
  double hedgePercentile = 0.95;
  double hedgeMinMs = 20.0;
  std::size_t hedgeMinSamples = 8;
};

// Which server traces which tile of one frame: pure logic, no sockets, no
// clock of its own (every call takes `now` in ms), so that it can be tested
// and simulated in virtual time (tests/support/dispatch_sim.h).
//
// - Tiles go out costliest first. A tile's cost is an estimate in any unit
//   (masked pixels times the effect plan's depth, or last frame's measured
//   milliseconds); only ratios between tiles and servers matter.
// - A server is kept fed with a window of outstanding work sized from its
//   pace: throughput times (round trip + lead), at least one tile per thread.
//   A lone server gets the whole frame at once: there is nothing to balance,
//   and glintd then writes results back in few large batches.
// - With no unassigned tile left, a server with idle threads takes a copy of
//   the oldest outstanding tile of the server that will finish last; and at
//   any time a tile outstanding past the frame's p95 latency is copied to the
//   least loaded server (a paused or slow server's tiles). The first result
//   wins and the other copy is to be cancelled.
// - A lost server's tiles that no other server holds go back to the queue;
//   a distrusted one's delivered tiles too.
class TileDispatcher {
 public:
  struct Assignment {
    std::size_t server;
    std::size_t tile;
  };
  struct Delivery {
    bool first = false;                 // false: another copy won; drop this result
    std::vector<std::size_t> cancelOn;  // servers that still hold a copy
  };

  // `servers` the farm's servers by index, of which those that join serve.
  TileDispatcher(std::vector<double> tileCosts, std::size_t servers, const DispatchSettings& settings);

  // The server is ready for this frame (scene present, frame set up); `pace`
  // is what earlier frames taught of it.
  void join(std::size_t server, const ServerPace& pace, double now);
  // Tiles to send now, each to one server.
  std::vector<Assignment> assign(double now);
  // `server` delivered `tile`, which took it `computeMs` to trace.
  Delivery deliver(std::size_t server, std::size_t tile, double now, double computeMs);
  // The server is gone for this frame; its tiles held by no one else are
  // queued again. Returns them.
  std::vector<std::size_t> lose(std::size_t server);
  // The server broke the protocol: besides losing it, the tiles whose
  // results it delivered this frame are queued again, as not to be trusted.
  // Returns those.
  std::vector<std::size_t> distrust(std::size_t server);
  // Servers with tiles outstanding that delivered nothing for the stall timeout.
  std::vector<std::size_t> stalled(double now) const;
  // The first time from `now` on when stalled() or assign() may find what no
  // delivery, join or loss brings: a stall, or a tile outstanding past the
  // hedging threshold (both hold just after it); infinity when none can.
  double nextCheck(double now);

  bool done() const { return delivered_ == costs_.size(); }
  double cost(std::size_t tile) const { return costs_[tile]; }
  // Joined servers not lost.
  std::size_t liveServers() const;
  bool joined(std::size_t server) const { return servers_[server].joined; }
  bool lost(std::size_t server) const { return servers_[server].lost; }
  std::size_t outstanding(std::size_t server) const { return servers_[server].outstanding.size(); }
  std::size_t reissued() const { return reissued_; }
  std::size_t duplicated() const { return duplicated_; }  // copies sent, hedged ones included
  std::size_t hedged() const { return hedged_; }
  bool wasReissued(std::size_t tile) const { return tiles_[tile].reissued; }
  // At the frame's end: folds this frame's measured pace into each joined
  // server's pace.
  void finish();
  // What a joined server's pace is now (after finish(), with this frame's).
  const ServerPace& pace(std::size_t server) const { return servers_[server].pace; }

 private:
  struct Sent {
    std::size_t tile;
    double at;
  };
  struct Server {
    ServerPace pace;
    bool joined = false;
    bool lost = false;
    double lastProgress = 0.0;  // last delivery, or when work was sent to an empty window
    double outstandingCost = 0.0;
    double tracedCost = 0.0;       // of every result it delivered, copies that lost included
    double tracedMs = 0.0;         // the tracing time it reported for them
    std::deque<Sent> outstanding;  // in the order sent
  };
  struct Tile {
    std::vector<std::size_t> holders;  // servers holding a copy
    std::size_t by = 0;                // the server whose result counts, once done
    bool done = false;
    bool reissued = false;
  };
  // Queue order: costliest first, then by index.
  struct CostlierFirst {
    const std::vector<double>* costs;
    bool operator()(std::size_t a, std::size_t b) const {
      return (*costs)[a] != (*costs)[b] ? (*costs)[a] > (*costs)[b] : a < b;
    }
  };

  bool live(std::size_t server) const { return servers_[server].joined && !servers_[server].lost; }
  bool hasRoom(std::size_t server) const;
  // When the server's outstanding work ends, in cost over its speed.
  double finishEstimate(std::size_t server) const;
  // Cost traced per ms: from this frame's results (their reported tracing
  // time, so that time a server waited is not counted against it), else
  // what earlier frames measured; 0 when nothing is known.
  double rate(std::size_t server) const;
  // The server whose outstanding work ends last (other than `except`) and its
  // oldest tile with one copy; false when there is none.
  bool pickDuplicate(std::size_t except, std::size_t& tile) const;
  void send(std::size_t server, std::size_t tile, double now, std::vector<Assignment>& out);
  // Its oldest outstanding tile was sent more than `after` ms ago.
  bool straggling(std::size_t server, double now, double after) const;
  // Copies of the tiles outstanding past the hedging threshold.
  void hedge(double now, std::vector<Assignment>& out);
  // The hedging threshold from this frame's latencies; < 0 while too few.
  double hedgeAfterMs();
  void removeOutstanding(std::size_t server, std::size_t tile);

  std::vector<double> costs_;
  DispatchSettings settings_;
  std::vector<Server> servers_;
  std::vector<Tile> tiles_;
  std::set<std::size_t, CostlierFirst> queue_;
  std::size_t delivered_ = 0;
  std::size_t reissued_ = 0;
  std::size_t duplicated_ = 0;
  std::size_t hedged_ = 0;
  std::vector<double> latencies_;  // this frame's tiles, sent to delivered
  std::size_t latenciesUsed_ = 0;  // how many the cached threshold saw
  double hedgeAfterMs_ = -1.0;
};

}  // namespace glint
