#include "tests/support/dispatch_sim.h"

#include <algorithm>
#include <deque>
#include <queue>

namespace glint::sim {
namespace {

constexpr double kTickMs = 5.0;    // how often the client checks for stalls
constexpr double kGiveUpMs = 1e7;  // a frame never takes this long in any model here

enum class Kind { kJoin, kRequest, kFinish, kResult, kCancel, kClosed, kTick };

struct Event {
  double at;
  std::size_t seq;  // ties in time keep their order
  Kind kind;
  std::size_t server;
  std::size_t tile;
  bool operator>(const Event& o) const { return at != o.at ? at > o.at : seq > o.seq; }
};

struct ServerState {
  std::deque<std::size_t> queue;
  int freeThreads = 0;
  double linkFreeAt = 0.0;
  bool lostByClient = false;
};

class Simulation {
 public:
  Simulation(const std::vector<SimTile>& tiles, const std::vector<double>& estimates,
             const std::vector<SimServer>& servers, Policy policy, const DispatchSettings& settings,
             std::vector<ServerPace>& paces, const SimClient& client)
      : tiles_(tiles),
        servers_(servers),
        client_(client),
        policy_(policy),
        paces_(paces),
        dispatcher_(estimates, paces.size(), settings),
        state_(servers.size()) {
    result_.firstDeliveries.assign(tiles.size(), 0);
    result_.busyMs.assign(servers.size(), 0.0);
    for (std::size_t s = 0; s < servers.size(); ++s) {
      state_[s].freeThreads = servers[s].threads;
      if (servers[s].joinAtMs < 0.0) {
        ++joinsSeen_;  // not a member: never joins
        continue;
      }
      push(servers[s].joinAtMs, Kind::kJoin, s);
      if (servers[s].lossAtMs >= 0.0 && !servers[s].silentLoss) {
        push(servers[s].lossAtMs + servers[s].rttMs / 2, Kind::kClosed, s);
      }
    }
    push(kTickMs, Kind::kTick, 0);
  }

  SimResult run() {
    while (!events_.empty() && delivered_ < tiles_.size()) {
      const Event e = events_.top();
      events_.pop();
      if (e.at > kGiveUpMs) break;
      handle(e);
      if (policy_ == Policy::kDispatcher) dispatch(e.at);
      if (delivered_ == tiles_.size()) finish(e.at);
      if (policy_ == Policy::kDispatcher && dispatcher_.liveServers() == 0 && joinsSeen_ == servers_.size()) break;
    }
    result_.reissued = dispatcher_.reissued();
    result_.duplicated = dispatcher_.duplicated();
    result_.hedged = dispatcher_.hedged();
    return result_;
  }

 private:
  void push(double at, Kind kind, std::size_t server, std::size_t tile = 0) {
    events_.push({at, seq_++, kind, server, tile});
  }
  bool dead(std::size_t s, double t) const { return servers_[s].lossAtMs >= 0.0 && t >= servers_[s].lossAtMs; }

  // A stopped server does nothing until it continues: what reaches it
  // waits, and a tile it was tracing ends as much later as the pause.
  bool deferredByPause(const Event& e) {
    const SimServer& s = servers_[e.server];
    const bool onServer = e.kind == Kind::kRequest || e.kind == Kind::kFinish || e.kind == Kind::kCancel;
    if (!onServer || s.pauseAtMs < 0.0 || e.at < s.pauseAtMs || e.at >= s.pauseAtMs + s.pauseForMs) return false;
    const double resume = s.pauseAtMs + s.pauseForMs;
    push(e.kind == Kind::kFinish ? resume + (e.at - s.pauseAtMs) : resume, e.kind, e.server, e.tile);
    return true;
  }

  void handle(const Event& e) {
    if (deferredByPause(e)) return;
    switch (e.kind) {
      case Kind::kJoin:
        return join(e.server, e.at);
      case Kind::kRequest:
        if (dead(e.server, e.at)) return;
        state_[e.server].queue.push_back(e.tile);
        return startWork(e.server, e.at);
      case Kind::kFinish:
        return finishTile(e.server, e.tile, e.at);
      case Kind::kResult:
        return result(e.server, e.tile, e.at);
      case Kind::kCancel:
        result_.cancelledQueued += std::erase(state_[e.server].queue, e.tile);
        return;
      case Kind::kClosed:
        return lose(e.server);
      case Kind::kTick:
        push(e.at + kTickMs, Kind::kTick, 0);
        return;
    }
  }

  void join(std::size_t s, double t) {
    ++joinsSeen_;
    if (dead(s, t)) return;
    if (policy_ == Policy::kDispatcher) {
      dispatcher_.join(s, paces_[s], t);
      return;
    }
    for (std::size_t tile = s; tile < tiles_.size(); tile += servers_.size()) {
      push(t + servers_[s].rttMs / 2, Kind::kRequest, s, tile);
    }
  }

  void startWork(std::size_t s, double t) {
    ServerState& st = state_[s];
    while (st.freeThreads > 0 && !st.queue.empty()) {
      const std::size_t tile = st.queue.front();
      st.queue.pop_front();
      --st.freeThreads;
      const double ms = tiles_[tile].ms / servers_[s].speed;
      result_.busyMs[s] += ms;
      push(t + ms, Kind::kFinish, s, tile);
    }
  }

  void finishTile(std::size_t s, std::size_t tile, double t) {
    ServerState& st = state_[s];
    ++st.freeThreads;
    if (dead(s, t)) return;
    const auto bytes = static_cast<double>(tiles_[tile].resultBytes);
    st.linkFreeAt = std::max(st.linkFreeAt, t) + bytes / servers_[s].bytesPerMs;
    double sent = st.linkFreeAt;
    if (client_.bytesPerMs > 0.0)
      sent = clientLinkFreeAt_ = std::max(clientLinkFreeAt_, sent) + bytes / client_.bytesPerMs;
    push(sent + servers_[s].rttMs / 2, Kind::kResult, s, tile);
    startWork(s, t);
  }

  void result(std::size_t s, std::size_t tile, double t) {
    if (state_[s].lostByClient) return;  // the client closed that connection
    if (policy_ == Policy::kStaticRoundRobin) {
      ++result_.firstDeliveries[tile];
      ++delivered_;
      return;
    }
    const TileDispatcher::Delivery d = dispatcher_.deliver(s, tile, t, tiles_[tile].ms / servers_[s].speed);
    if (!d.first) {
      result_.wastedMs += tiles_[tile].ms / servers_[s].speed;
      return;
    }
    ++result_.firstDeliveries[tile];
    ++delivered_;
    for (const std::size_t other : d.cancelOn) push(t + servers_[other].rttMs / 2, Kind::kCancel, other, tile);
  }

  void lose(std::size_t s) {
    if (policy_ != Policy::kDispatcher || state_[s].lostByClient || !dispatcher_.joined(s)) return;
    state_[s].lostByClient = true;
    dispatcher_.lose(s);
  }

  void dispatch(double t) {
    for (const std::size_t s : dispatcher_.stalled(t)) lose(s);
    for (const TileDispatcher::Assignment& a : dispatcher_.assign(t)) {
      push(t + servers_[a.server].rttMs / 2, Kind::kRequest, a.server, a.tile);
    }
  }

  void finish(double t) {
    result_.completed = true;
    result_.frameMs = t;
    if (policy_ != Policy::kDispatcher) return;
    dispatcher_.finish();
    for (std::size_t s = 0; s < paces_.size(); ++s) {
      if (dispatcher_.joined(s)) paces_[s] = dispatcher_.pace(s);
    }
  }

  const std::vector<SimTile>& tiles_;
  const std::vector<SimServer>& servers_;
  SimClient client_;
  double clientLinkFreeAt_ = 0.0;
  Policy policy_;
  std::vector<ServerPace>& paces_;  // what the dispatcher is told at a join, and learns back at the end
  TileDispatcher dispatcher_;
  std::vector<ServerState> state_;
  std::priority_queue<Event, std::vector<Event>, std::greater<>> events_;
  std::size_t seq_ = 0;
  std::size_t delivered_ = 0;
  std::size_t joinsSeen_ = 0;
  SimResult result_;
};

}  // namespace

SimResult simulateFrame(const std::vector<SimTile>& tiles, const std::vector<double>& estimates,
                        const std::vector<SimServer>& servers, Policy policy, const DispatchSettings& settings,
                        std::vector<ServerPace>& paces, const SimClient& client) {
  return Simulation(tiles, estimates, servers, policy, settings, paces, client).run();
}

double idealMs(const std::vector<SimTile>& tiles, const std::vector<SimServer>& servers, const SimClient& client) {
  double work = 0.0;
  double bytes = 0.0;
  for (const SimTile& t : tiles) {
    work += t.ms;
    bytes += static_cast<double>(t.resultBytes);
  }
  double speed = 0.0;
  for (const SimServer& s : servers) speed += s.speed * s.threads;
  return std::max(work / speed, client.bytesPerMs > 0.0 ? bytes / client.bytesPerMs : 0.0);
}

}  // namespace glint::sim
