#include "client/farm/tile_dispatcher.h"

#include <algorithm>
#include <cassert>
#include <limits>

namespace glint {
namespace {

// A frame's measured pace counts this much against what earlier frames
// taught (view and --frames: the camera moves, the server's load changes).
constexpr double kPaceWeight = 0.5;

}  // namespace

TileDispatcher::TileDispatcher(std::vector<double> tileCosts, std::size_t servers, const DispatchSettings& settings)
    : costs_(std::move(tileCosts)),
      settings_(settings),
      servers_(servers),
      tiles_(costs_.size()),
      queue_(CostlierFirst{&costs_}) {
  for (std::size_t t = 0; t < costs_.size(); ++t) queue_.insert(t);
}

void TileDispatcher::join(std::size_t server, const ServerPace& pace, double now) {
  Server& s = servers_[server];
  if (s.joined) return;
  s.joined = true;
  s.pace = pace;
  s.lastProgress = now;
}

std::size_t TileDispatcher::liveServers() const {
  std::size_t n = 0;
  for (std::size_t s = 0; s < servers_.size(); ++s) n += live(s) ? 1 : 0;
  return n;
}

double TileDispatcher::finishEstimate(std::size_t server) const {
  const double r = rate(server);
  return servers_[server].outstandingCost / (r > 0.0 ? r : std::max(1, servers_[server].pace.threads));
}

double TileDispatcher::rate(std::size_t server) const {
  const Server& s = servers_[server];
  if (s.tracedMs <= 0.0) return servers_[server].pace.costPerMs;
  return std::max(1, servers_[server].pace.threads) * s.tracedCost / s.tracedMs;
}

bool TileDispatcher::hasRoom(std::size_t server) const {
  const Server& s = servers_[server];
  const ServerPace& pace = s.pace;
  const auto threads = static_cast<std::size_t>(std::max(1, pace.threads));
  if (s.outstanding.size() < threads || servers_.size() == 1) return true;  // one server: nothing to balance
  if (pace.costPerMs <= 0.0 || pace.rttMs < 0.0) {
    return s.outstanding.size() < threads * static_cast<std::size_t>(settings_.initialTilesPerThread);
  }
  return s.outstandingCost < pace.costPerMs * (pace.rttMs + settings_.leadMs);
}

void TileDispatcher::send(std::size_t server, std::size_t tile, double now, std::vector<Assignment>& out) {
  Server& s = servers_[server];
  if (s.outstanding.empty()) s.lastProgress = now;
  s.outstanding.push_back({tile, now});
  s.outstandingCost += costs_[tile];
  tiles_[tile].holders.push_back(server);
  out.push_back({server, tile});
}

// Longest processing time first: each tile, costliest first, goes to the
// server with room that would finish its outstanding work soonest.
std::vector<TileDispatcher::Assignment> TileDispatcher::assign(double now) {
  std::vector<Assignment> out;
  hedge(now, out);
  while (!queue_.empty()) {
    std::size_t best = servers_.size();
    double soonest = std::numeric_limits<double>::max();
    for (std::size_t s = 0; s < servers_.size(); ++s) {
      if (!live(s) || !hasRoom(s)) continue;
      const double finish = finishEstimate(s);
      if (finish < soonest) {
        soonest = finish;
        best = s;
      }
    }
    if (best == servers_.size()) return out;
    const std::size_t tile = *queue_.begin();
    queue_.erase(queue_.begin());
    send(best, tile, now, out);
  }
  // Nothing fresh: servers with idle threads take copies of the last bucket.
  for (std::size_t s = 0; s < servers_.size(); ++s) {
    if (!live(s)) continue;
    const auto threads = static_cast<std::size_t>(std::max(1, servers_[s].pace.threads));
    std::size_t tile = 0;
    while (servers_[s].outstanding.size() < threads && pickDuplicate(s, tile)) {
      send(s, tile, now, out);
      ++duplicated_;
    }
  }
  return out;
}

double TileDispatcher::hedgeAfterMs() {
  if (latencies_.size() < settings_.hedgeMinSamples) return -1.0;
  if (latenciesUsed_ != latencies_.size()) {
    std::vector<double> sorted = latencies_;
    const auto rank = static_cast<std::size_t>(settings_.hedgePercentile * static_cast<double>(sorted.size() - 1));
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(rank), sorted.end());
    hedgeAfterMs_ = std::max(settings_.hedgeMinMs, sorted[rank]);
    latenciesUsed_ = latencies_.size();
  }
  return hedgeAfterMs_;
}

bool TileDispatcher::straggling(std::size_t server, double now, double after) const {
  const Server& s = servers_[server];
  return !s.outstanding.empty() && now - s.outstanding.front().at > after;
}

// Each tile whose every holder is straggling gets a copy on the least
// loaded server that is not: a copy sent to a server that then stops too
// is copied again.
void TileDispatcher::hedge(double now, std::vector<Assignment>& out) {
  if (!settings_.hedge) return;
  const double after = hedgeAfterMs();
  if (after < 0.0) return;
  const auto leastLoaded = [&] {
    std::size_t target = servers_.size();
    for (std::size_t s = 0; s < servers_.size(); ++s) {
      if (!live(s) || straggling(s, now, after)) continue;
      if (target == servers_.size() || finishEstimate(s) < finishEstimate(target)) target = s;
    }
    return target;
  };
  for (std::size_t s = 0; s < servers_.size(); ++s) {
    if (!live(s)) continue;
    for (const Sent& sent : servers_[s].outstanding) {
      if (now - sent.at <= after) break;  // sent in order: the rest are younger
      const std::vector<std::size_t>& holders = tiles_[sent.tile].holders;
      const bool stuck =
          std::all_of(holders.begin(), holders.end(), [&](std::size_t h) { return straggling(h, now, after); });
      if (!stuck) continue;
      const std::size_t target = leastLoaded();
      if (target == servers_.size()) return;
      send(target, sent.tile, now, out);
      ++duplicated_;
      ++hedged_;
    }
  }
}

bool TileDispatcher::pickDuplicate(std::size_t except, std::size_t& tile) const {
  double latest = -1.0;
  bool found = false;
  for (std::size_t s = 0; s < servers_.size(); ++s) {
    const Server& server = servers_[s];
    if (s == except || !live(s)) continue;
    const auto candidate = std::find_if(server.outstanding.begin(), server.outstanding.end(),
                                        [&](const Sent& sent) { return tiles_[sent.tile].holders.size() == 1; });
    if (candidate == server.outstanding.end()) continue;
    const double r = rate(s);
    const double ends = r > 0.0 ? server.outstandingCost / r : std::numeric_limits<double>::max();
    if (ends > latest) {
      latest = ends;
      tile = candidate->tile;
      found = true;
    }
  }
  return found;
}

void TileDispatcher::removeOutstanding(std::size_t server, std::size_t tile) {
  Server& s = servers_[server];
  const auto it =
      std::find_if(s.outstanding.begin(), s.outstanding.end(), [tile](const Sent& x) { return x.tile == tile; });
  if (it == s.outstanding.end()) return;
  s.outstanding.erase(it);
  s.outstandingCost = s.outstanding.empty() ? 0.0 : s.outstandingCost - costs_[tile];
  std::erase(tiles_[tile].holders, server);
}

TileDispatcher::Delivery TileDispatcher::deliver(std::size_t server, std::size_t tile, double now, double computeMs) {
  Server& s = servers_[server];
  const auto sent =
      std::find_if(s.outstanding.begin(), s.outstanding.end(), [tile](const Sent& x) { return x.tile == tile; });
  if (sent != s.outstanding.end()) {
    const double overhead = std::max(0.0, now - sent->at - computeMs);
    ServerPace& pace = s.pace;
    pace.rttMs = pace.rttMs < 0.0 ? overhead : std::min(pace.rttMs, overhead);
    s.tracedCost += costs_[tile];
    s.tracedMs += computeMs;
    latencies_.push_back(now - sent->at);
  }
  s.lastProgress = now;
  removeOutstanding(server, tile);
  Delivery d;
  Tile& t = tiles_[tile];
  if (t.done) return d;
  t.done = true;
  t.by = server;
  ++delivered_;
  d.first = true;
  d.cancelOn = t.holders;
  for (const std::size_t other : d.cancelOn) removeOutstanding(other, tile);
  return d;
}

std::vector<std::size_t> TileDispatcher::lose(std::size_t server) {
  Server& s = servers_[server];
  s.lost = true;
  std::vector<std::size_t> requeued;
  while (!s.outstanding.empty()) {
    const std::size_t tile = s.outstanding.front().tile;
    removeOutstanding(server, tile);
    Tile& t = tiles_[tile];
    if (t.done || !t.holders.empty()) continue;
    t.reissued = true;
    queue_.insert(tile);
    requeued.push_back(tile);
    ++reissued_;
  }
  return requeued;
}

std::vector<std::size_t> TileDispatcher::distrust(std::size_t server) {
  std::vector<std::size_t> requeued = lose(server);
  for (std::size_t tile = 0; tile < tiles_.size(); ++tile) {
    Tile& t = tiles_[tile];
    if (!t.done || t.by != server) continue;
    t.done = false;
    --delivered_;
    t.reissued = true;
    queue_.insert(tile);
    requeued.push_back(tile);
    ++reissued_;
  }
  return requeued;
}

std::vector<std::size_t> TileDispatcher::stalled(double now) const {
  std::vector<std::size_t> out;
  for (std::size_t s = 0; s < servers_.size(); ++s) {
    const Server& server = servers_[s];
    if (live(s) && !server.outstanding.empty() && now - server.lastProgress > settings_.stallTimeoutMs) {
      out.push_back(s);
    }
  }
  return out;
}

double TileDispatcher::nextCheck(double now) {
  const double after = settings_.hedge ? hedgeAfterMs() : -1.0;
  double next = std::numeric_limits<double>::infinity();
  const auto consider = [&](double at) {
    if (at >= now) next = std::min(next, at);  // one past is what a check found and left
  };
  for (std::size_t s = 0; s < servers_.size(); ++s) {
    const Server& server = servers_[s];
    if (!live(s) || server.outstanding.empty()) continue;
    consider(server.lastProgress + settings_.stallTimeoutMs);
    if (after >= 0.0) consider(server.outstanding.front().at + after);
  }
  return next;
}

void TileDispatcher::finish() {
  for (std::size_t s = 0; s < servers_.size(); ++s) {
    const Server& server = servers_[s];
    if (!live(s) || server.tracedMs <= 0.0) continue;
    const double measured = rate(s);
    ServerPace& pace = servers_[s].pace;
    pace.costPerMs = pace.costPerMs > 0.0 ? kPaceWeight * measured + (1.0 - kPaceWeight) * pace.costPerMs : measured;
  }
}

}  // namespace glint
