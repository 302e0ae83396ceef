// The client's tile dispatcher: step by step, then whole frames in virtual
// time (tests/support/dispatch_sim) with slow and lost servers.
#include "client/farm/tile_dispatcher.h"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "tests/support/dispatch_sim.h"

namespace glint {
namespace {

using Assignments = std::vector<TileDispatcher::Assignment>;

std::vector<std::size_t> tilesOf(const Assignments& a, std::size_t server) {
  std::vector<std::size_t> out;
  for (const auto& x : a) {
    if (x.server == server) out.push_back(x.tile);
  }
  return out;
}

std::vector<ServerPace> paces(std::size_t servers, int threads) {
  std::vector<ServerPace> p(servers);
  for (ServerPace& x : p) x.threads = threads;
  return p;
}

TEST(TileDispatcher, CostliestTilesGoFirstAndOnlyToJoinedServers) {
  auto pace = paces(2, 1);
  TileDispatcher d({1.0, 5.0, 3.0, 5.0, 2.0}, pace.size(), {});
  EXPECT_TRUE(d.assign(0.0).empty());  // nobody joined yet
  d.join(0, pace[0], 0.0);
  // Pace unknown: two tiles per thread, the costliest, ties by index.
  EXPECT_EQ(tilesOf(d.assign(0.0), 0), (std::vector<std::size_t>{1, 3}));
  d.join(1, pace[1], 1.0);
  EXPECT_EQ(tilesOf(d.assign(1.0), 1), (std::vector<std::size_t>{2, 4}));
  EXPECT_TRUE(d.assign(1.0).empty());  // both windows full
  EXPECT_TRUE(d.deliver(0, 1, 2.0, 1.0).first);
  EXPECT_EQ(tilesOf(d.assign(2.0), 0), (std::vector<std::size_t>{0}));
}

// The first copy of a tile wins; the dispatcher names the server holding
// the other so that it can be cancelled, and the late copy is dropped.
TEST(TileDispatcher, AnIdleServerCopiesTheLastBucketAndTheLoserIsCancelled) {
  auto pace = paces(2, 1);
  DispatchSettings settings;
  settings.initialTilesPerThread = 1;
  TileDispatcher d({4.0, 1.0}, pace.size(), settings);
  d.join(0, pace[0], 0.0);
  d.join(1, pace[1], 0.0);
  const Assignments first = d.assign(0.0);
  EXPECT_EQ(tilesOf(first, 0), (std::vector<std::size_t>{0}));
  EXPECT_EQ(tilesOf(first, 1), (std::vector<std::size_t>{1}));
  EXPECT_TRUE(d.deliver(1, 1, 1.0, 1.0).first);
  // Nothing fresh is left: server 1 takes a copy of server 0's tile.
  EXPECT_EQ(tilesOf(d.assign(1.0), 1), (std::vector<std::size_t>{0}));
  EXPECT_EQ(d.duplicated(), 1u);
  const TileDispatcher::Delivery won = d.deliver(1, 0, 2.0, 1.0);
  EXPECT_TRUE(won.first);
  EXPECT_EQ(won.cancelOn, (std::vector<std::size_t>{0}));
  EXPECT_TRUE(d.done());
  EXPECT_EQ(d.outstanding(0), 0u);
  EXPECT_FALSE(d.deliver(0, 0, 3.0, 3.0).first);  // the cancelled copy, had it run
}

// A tile held past the frame's p95 latency (and the minimum) is copied to
// a server that answers, while fresh tiles remain, and only once; the copy's
// result wins and the stuck server's copy is to be cancelled.
TEST(TileDispatcher, ATileHeldPastTheP95IsHedgedToAnotherServer) {
  auto pace = paces(3, 1);
  DispatchSettings settings;
  settings.initialTilesPerThread = 1;
  settings.hedgeMinSamples = 4;
  settings.hedgeMinMs = 5.0;
  TileDispatcher d(std::vector<double>(40, 1.0), pace.size(), settings);
  for (std::size_t s = 0; s < 3; ++s) d.join(s, pace[s], 0.0);
  std::vector<std::vector<std::size_t>> held(3);
  const auto take = [&](const Assignments& sent) {
    for (const auto& a : sent) held[a.server].push_back(a.tile);
  };
  take(d.assign(0.0));
  const std::size_t stuck = held[2].front();  // server 2 never answers
  // Servers 0 and 1 answer each tile 2 ms after it was sent.
  std::size_t copiedTo = 3;
  for (double now = 2.0; now <= 12.0; now += 2.0) {
    for (std::size_t s = 0; s < 2; ++s) {
      for (const std::size_t tile : held[s]) {
        const TileDispatcher::Delivery won = d.deliver(s, tile, now, 2.0);
        if (tile == stuck) {
          EXPECT_TRUE(won.first);
          EXPECT_EQ(won.cancelOn, (std::vector<std::size_t>{2}));
        }
      }
      held[s].clear();
    }
    const Assignments sent = d.assign(now);
    take(sent);
    // Until 6 ms the stuck tile is younger than the 5 ms minimum (the p95 is 2 ms).
    EXPECT_EQ(d.hedged(), now < 6.0 ? 0u : 1u) << now << " ms";
    // With four latencies known, the next check is when the stuck tile turns 5 ms old.
    if (now == 4.0) {
      EXPECT_EQ(d.nextCheck(now), 5.0);
    }
    for (const auto& a : sent) {
      if (a.tile == stuck) copiedTo = a.server;
    }
  }
  EXPECT_LT(copiedTo, 2u);
  EXPECT_EQ(d.duplicated(), 1u);
}

TEST(TileDispatcher, ALostServersTilesAreReissuedAndAStalledOneIsNamed) {
  auto pace = paces(2, 1);
  DispatchSettings settings;
  settings.stallTimeoutMs = 100.0;
  TileDispatcher d({1.0, 1.0, 1.0, 1.0}, pace.size(), settings);
  d.join(0, pace[0], 0.0);
  d.join(1, pace[1], 0.0);
  d.assign(0.0);
  EXPECT_EQ(d.nextCheck(0.0), 100.0);  // when a stall could first be seen
  EXPECT_TRUE(d.stalled(100.0).empty());
  d.deliver(1, 1, 50.0, 1.0);
  EXPECT_EQ(d.stalled(101.0), (std::vector<std::size_t>{0}));  // server 1 delivered at 50
  EXPECT_EQ(d.nextCheck(101.0), 150.0);  // a stall found is not due again; server 1's is next
  const std::vector<std::size_t> back = d.lose(0);
  EXPECT_EQ(back, (std::vector<std::size_t>{0, 2}));
  EXPECT_EQ(d.reissued(), 2u);
  EXPECT_TRUE(d.wasReissued(0));
  EXPECT_EQ(d.liveServers(), 1u);
  EXPECT_TRUE(tilesOf(d.assign(101.0), 0).empty());  // a lost server gets nothing more
}

// A server's window grows with its measured throughput: a fast server holds
// more outstanding work than a slow one once the pace is known.
TEST(TileDispatcher, WindowsFollowMeasuredPace) {
  std::vector<sim::SimTile> tiles(400, {1.0, 12000});
  std::vector<double> estimates(tiles.size(), 1.0);
  std::vector<sim::SimServer> servers(2);
  servers[0].speed = 4.0;
  servers[0].threads = servers[1].threads = 2;
  auto pace = paces(2, 2);
  sim::simulateFrame(tiles, estimates, servers, sim::Policy::kDispatcher, {}, pace);
  EXPECT_GT(pace[0].costPerMs, 3.0 * pace[1].costPerMs);
  EXPECT_GE(pace[0].rttMs, 0.0);
  TileDispatcher d(estimates, pace.size(), {});
  d.join(0, pace[0], 0.0);
  d.join(1, pace[1], 0.0);
  const Assignments a = d.assign(0.0);
  EXPECT_GT(tilesOf(a, 0).size(), 2 * tilesOf(a, 1).size());
}

double efficiency(const sim::SimResult& r, const std::vector<sim::SimTile>& tiles,
                  const std::vector<sim::SimServer>& servers) {
  return sim::idealMs(tiles, servers) / r.frameMs;
}

// Uneven tiles (a few costly ones, like a reflective object's), one server
// 4x slower than the others: the frame ends within 1.2x the ideal, where the
// static round robin waits for the slow server's share.
TEST(TileDispatcher, OneSlowServerCostsLittle) {
  std::mt19937 rng(7);
  std::lognormal_distribution<double> cost(0.0, 1.0);
  std::vector<sim::SimTile> tiles(500);
  std::vector<double> estimates;
  for (sim::SimTile& t : tiles) {
    t.ms = cost(rng);
    t.resultBytes = 12000;
    estimates.push_back(t.ms);
  }
  std::vector<sim::SimServer> servers(4);
  servers[3].speed = 0.25;
  auto pace = paces(4, 1);
  const sim::SimResult ours = sim::simulateFrame(tiles, estimates, servers, sim::Policy::kDispatcher, {}, pace);
  auto paceRr = paces(4, 1);
  const sim::SimResult rr = sim::simulateFrame(tiles, estimates, servers, sim::Policy::kStaticRoundRobin, {}, paceRr);
  ASSERT_TRUE(ours.completed);
  ASSERT_TRUE(rr.completed);
  EXPECT_LE(ours.frameMs, 1.2 * sim::idealMs(tiles, servers));
  EXPECT_LT(ours.frameMs, rr.frameMs);
  EXPECT_GT(efficiency(ours, tiles, servers), 0.83);
  for (int n : ours.firstDeliveries) EXPECT_EQ(n, 1);
}

// 1000 frames with servers lost at random moments (closing or stalling),
// joining late, of random speeds: every tile reaches the frame exactly once
// whenever a server survives, and a frame with none left ends instead of
// waiting forever.
TEST(TileDispatcher, ThousandFramesWithRandomLosses) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int completed = 0;
  int hopeless = 0;
  for (int frame = 0; frame < 1000; ++frame) {
    std::vector<sim::SimTile> tiles(10 + rng() % 200);
    std::vector<double> estimates;
    for (sim::SimTile& t : tiles) {
      t.ms = 0.1 + 5.0 * unit(rng);
      t.resultBytes = 1000 + rng() % 20000;
      estimates.push_back(t.ms * (0.5 + unit(rng)));  // estimates are rough
    }
    std::vector<sim::SimServer> servers(1 + rng() % 8);
    bool survivor = false;
    for (sim::SimServer& s : servers) {
      s.threads = 1 + static_cast<int>(rng() % 4);
      s.speed = 0.25 + 2.0 * unit(rng);
      s.rttMs = 0.1 + 2.0 * unit(rng);
      s.joinAtMs = unit(rng) < 0.3 ? 50.0 * unit(rng) : 0.0;
      if (unit(rng) < 0.4) {
        s.lossAtMs = 100.0 * unit(rng);
        s.silentLoss = unit(rng) < 0.5;
      } else {
        survivor = true;
      }
    }
    DispatchSettings settings;
    settings.stallTimeoutMs = 20.0;
    std::vector<ServerPace> pace(servers.size());
    for (std::size_t s = 0; s < servers.size(); ++s) pace[s].threads = servers[s].threads;
    const sim::SimResult r = sim::simulateFrame(tiles, estimates, servers, sim::Policy::kDispatcher, settings, pace);
    if (survivor) {
      ASSERT_TRUE(r.completed) << "frame " << frame;
    }
    if (r.completed) {
      ++completed;
      for (std::size_t t = 0; t < tiles.size(); ++t) ASSERT_EQ(r.firstDeliveries[t], 1) << "frame " << frame;
    } else {
      ++hopeless;
      ASSERT_FALSE(survivor);
    }
  }
  EXPECT_GT(completed, 900);
  EXPECT_GT(hopeless, 0);  // the run did meet frames with every server lost
}

// One farm over 1000 frames that changes between frames (servers join and
// leave, as with --server-file; paces carry over), with servers that join a
// frame late, slow ones, and ones stopped (SIGSTOP) for 2 s mid-frame: every
// tile reaches each frame exactly once, a server not in the farm never
// traces, and no frame waits for a stopped server while another is up (the
// 2 s stall timeout is never reached: its tiles are copied).
TEST(TileDispatcher, ThousandFramesOfAFarmThatChanges) {
  std::mt19937 rng(36);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<sim::SimServer> farm(8);
  for (sim::SimServer& s : farm) {
    s.threads = 1 + static_cast<int>(rng() % 4);
    s.speed = unit(rng) < 0.2 ? 0.25 : 0.5 + unit(rng);
    s.rttMs = 0.1 + unit(rng);
  }
  std::vector<bool> member{true, true, true, false, false, false, false, false};
  std::vector<ServerPace> pace(farm.size());
  std::size_t hedged = 0;
  std::size_t paused = 0;
  for (int frame = 0; frame < 1000; ++frame) {
    for (std::size_t s = 0; s < farm.size(); ++s) {
      if (unit(rng) < 0.1) member[s] = !member[s];
    }
    member[rng() % farm.size()] = true;
    std::vector<sim::SimTile> tiles(10 + rng() % 150);
    std::vector<double> estimates;
    for (sim::SimTile& t : tiles) {
      t.ms = 0.2 + 4.0 * unit(rng);
      estimates.push_back(t.ms * (0.5 + unit(rng)));
    }
    std::vector<sim::SimServer> servers = farm;
    std::size_t running = 0;
    for (std::size_t s = 0; s < servers.size(); ++s) {
      servers[s].joinAtMs = !member[s] ? -1.0 : unit(rng) < 0.1 ? 20.0 * unit(rng) : 0.0;
      if (member[s] && unit(rng) < 0.15) {
        servers[s].pauseAtMs = 30.0 * unit(rng);
        servers[s].pauseForMs = 2000.0;
        ++paused;
      } else if (member[s]) {
        ++running;
      }
    }
    for (std::size_t s = 0; s < servers.size(); ++s) pace[s].threads = servers[s].threads;
    const sim::SimResult r = sim::simulateFrame(tiles, estimates, servers, sim::Policy::kDispatcher, {}, pace);
    ASSERT_TRUE(r.completed) << "frame " << frame;
    for (std::size_t t = 0; t < tiles.size(); ++t) ASSERT_EQ(r.firstDeliveries[t], 1) << "frame " << frame;
    for (std::size_t s = 0; s < servers.size(); ++s) {
      if (!member[s]) {
        ASSERT_EQ(r.busyMs[s], 0.0) << "frame " << frame << " server " << s;
      }
    }
    if (running > 0) {
      EXPECT_LT(r.frameMs, 2000.0) << "frame " << frame;
    }
    hedged += r.hedged;
  }
  EXPECT_GT(paused, 100u);  // the run did stop servers mid-frame
  EXPECT_GT(hedged, 0u);
}

}  // namespace
}  // namespace glint
