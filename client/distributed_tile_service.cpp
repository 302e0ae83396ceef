#include "client/distributed_tile_service.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <thread>

#include "common/base/error.h"

namespace glint {
namespace {

constexpr std::chrono::milliseconds kStep{5};          // how often stalls are checked while waiting
constexpr std::chrono::seconds kGoodbyeGrace{1};       // for the Goodbyes to be written at the end

}  // namespace

struct DistributedTileService::Frame {
  std::uint32_t id;
  const FrameSettings& settings;
  std::span<const TileJob> jobs;
  const std::function<void(std::size_t, TileOutput&&)>& done;
  std::vector<std::size_t> sent;  // the dispatcher's tile -> the job's index
  std::vector<double> costs;
  TileDispatcher dispatcher;
  // Results held until the frame is whole, by the dispatcher's tile, with
  // the server each came from: a server caught lying drops its own.
  std::vector<std::optional<TileOutput>> outputs;
  std::vector<std::size_t> from;
  std::size_t traced = 0;
  std::vector<std::uint64_t> bytesIn;   // per server, at the frame's start
  std::vector<std::uint64_t> bytesOut;
  std::size_t reportBase = 0;  // report_'s index of jobs[0]
  std::vector<std::size_t> tracedBy{};  // per server: results held from it
};

DistributedTileService::DistributedTileService(ServerSource servers, const proto::SceneBundle& bundle,
                                               const DistributedSettings& settings)
    : source_(std::move(servers)),
      digest_(proto::digest(bundle)),
      settings_(settings),
      servers_(io_, source_.addresses(), bundle, digest_, settings.timeouts, settings.tls, *this) {
  paces_.resize(servers_.size());
  while (settings.awaitOne && serversUp() == 0) {
    if (sceneError_) throw InputError(*sceneError_);
    throwIfHopeless();
    io_.run_one();
  }
}

DistributedTileService::~DistributedTileService() {
  servers_.closeAll();
  io_.restart();
  io_.run_for(kGoodbyeGrace);
}

void DistributedTileService::awaitServers(std::chrono::milliseconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (servers_.anyConnecting() && std::chrono::steady_clock::now() < deadline) {
    if (io_.stopped()) io_.restart();
    io_.run_one_until(deadline);
  }
}

void DistributedTileService::refresh() {
  adoptChanges(reportFrame_ + 1);
  if (io_.stopped()) io_.restart();
  io_.poll();
}

void DistributedTileService::adoptChanges(int frame) {
  const bool changed = source_.refresh(std::chrono::steady_clock::now());
  if (source_.warning() != warned_ && !source_.warning().empty()) {
    std::fprintf(stderr, "glint: warning: %s\n", source_.warning().c_str());
  }
  warned_ = source_.warning();
  if (!changed || !servers_.adopt(source_.addresses(), frame)) return;
  paces_.resize(servers_.size());
}

double DistributedTileService::nowMs() const {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - epoch_).count();
}

std::size_t DistributedTileService::serversUp() const { return servers_.up(); }

bool DistributedTileService::uploaded() const { return servers_.anyUploaded(); }

int DistributedTileService::parallelism() const { return std::max(1, servers_.threadsUp()); }

// No server serves the frame and none is still on its way: a server that
// answered Busy is tried again when its backoff ends, within the scene
// timeout of its first Busy; failing that, the frame fails, one line each.
void DistributedTileService::throwIfHopeless() {
  if (servers_.anyConnecting() || (frame_ ? frame_->dispatcher.liveServers() > 0 : serversUp() > 0)) return;
  const auto retry = servers_.nextBusyRetry(settings_.timeouts.scene);
  if (!retry) throw InputError("no glintd can serve this frame:" + servers_.states());
  const double seconds = std::chrono::duration<double>(*retry - std::chrono::steady_clock::now()).count();
  std::fprintf(stderr, "glint: every glintd is busy; trying again in %.0f s\n", std::max(0.0, seconds));
  std::this_thread::sleep_until(*retry);
  servers_.retryLost();
}

void DistributedTileService::linkReady(ServerLink& link) {
  servers_.ready(link.index());
  paces_[link.index()].threads = link.threads();
  if (frame_) joinFrame(link.index());
}

void DistributedTileService::linkFailed(ServerLink& link, const LinkFailure& failure) {
  servers_.failed(link.index(), failure);
  if (failure.kind == LinkFailure::Kind::kSceneError && !sceneError_) {
    sceneError_ = "server " + servers_[link.index()].address.name + ": " + failure.what;
  }
  if (!frame_ || !frame_->dispatcher.joined(link.index()) || frame_->dispatcher.lost(link.index())) return;
  if (failure.kind != LinkFailure::Kind::kBadBytes) {
    frame_->dispatcher.lose(link.index());
    return;
  }
  for (const std::size_t tile : frame_->dispatcher.distrust(link.index())) {
    if (frame_->outputs[tile]) {
      --frame_->traced;
      --frame_->tracedBy[frame_->from[tile]];
    }
    frame_->outputs[tile].reset();
  }
  traced(frame_->traced);
}

void DistributedTileService::joinFrame(std::size_t index) {
  servers_[index].link->setupFrame(frame_->id, frame_->settings);
  frame_->dispatcher.join(index, nowMs());
}

void DistributedTileService::linkResult(ServerLink& link, std::uint32_t frameId, std::uint32_t tileId,
                                        TileOutput&& out) {
  if (!frame_ || frameId != frame_->id || tileId >= frame_->sent.size()) return;  // a cancelled copy, late
  const std::size_t index = link.index();
  const TileDispatcher::Delivery d = frame_->dispatcher.deliver(index, tileId, nowMs(), out.computeMs);
  if (!d.first) return;
  for (const std::size_t other : d.cancelOn) servers_[other].link->cancel(frameId, std::span(&tileId, 1));
  frame_->outputs[tileId] = std::move(out);
  frame_->from[tileId] = index;
  ++frame_->tracedBy[index];
  traced(++frame_->traced);
}

// The frame is whole: each result to the caller, and to the report.
void DistributedTileService::deliverFrame(Frame& frame) {
  for (std::size_t tile = 0; tile < frame.sent.size(); ++tile) {
    TileOutput& out = *frame.outputs[tile];
    const std::size_t job = frame.sent[tile];
    ServerReport& r = servers_[frame.from[tile]].report;
    ++r.tiles;
    r.maskedPixels += out.rgb.size() / 3;
    r.rays += out.rays;
    r.busyMs += out.computeMs;
    report_.deliveredBy[frame.reportBase + job] = rowOf_[frame.from[tile]];
    costs_.record(frame.jobs[job], frame.costs[tile], out.computeMs);
    frame.done(job, std::move(out));
  }
}

void DistributedTileService::render(const FrameSettings& settings, std::span<const TileJob> jobs,
                                    const std::function<void(std::size_t, TileOutput&&)>& done) {
  servers_.retryLost();
  std::vector<std::size_t> sent;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (tracedPixels(jobs[j]) > 0) {
      sent.push_back(j);
    } else {
      done(j, TileOutput{});
    }
  }
  std::vector<double> costs = costs_.costs(jobs, sent);
  DispatchSettings dispatch;
  dispatch.stallTimeoutMs = static_cast<double>(settings_.stallTimeout.count());
  const std::size_t tiles = sent.size();
  frame_.reset(new Frame{++frameId_, settings, jobs, done, std::move(sent), costs,
                         TileDispatcher(costs, paces_, dispatch), std::vector<std::optional<TileOutput>>(tiles),
                         std::vector<std::size_t>(tiles), 0, {}, {}});
  struct EndOfFrame {  // however render() ends
    std::unique_ptr<Frame>& frame;
    ~EndOfFrame() { frame.reset(); }
  } end{frame_};
  Frame& frame = *frame_;
  frame.tracedBy.assign(servers_.size(), 0);
  startReport(frame);
  try {
    for (std::size_t i = 0; i < servers_.size(); ++i) {
      if (servers_.serving(i)) joinFrame(i);
    }
    while (!frame.dispatcher.done()) {
      if (sceneError_) throw InputError(*sceneError_);
      throwIfHopeless();
      step();
    }
  } catch (...) {
    for (ServerPool::Server& s : servers_.all()) s.link->cancel(frame.id, {});
    throw;
  }
  frame.dispatcher.finish();
  deliverFrame(frame);
  finishReport(frame);
}

void DistributedTileService::step() {
  Frame& f = *frame_;
  for (const TileDispatcher::Assignment& a : f.dispatcher.assign(nowMs())) {
    servers_[a.server].link->request(f.id, static_cast<std::uint32_t>(a.tile), f.jobs[f.sent[a.tile]]);
  }
  if (io_.stopped()) io_.restart();
  io_.run_one_for(kStep);
  io_.poll();
  for (const std::size_t s : f.dispatcher.stalled(nowMs())) {
    servers_[s].link->fail(LinkFailure::Kind::kStalled,
                           "stalled: delivered nothing for " + std::to_string(settings_.stallTimeout.count()) +
                               " ms with tiles outstanding (--stall-timeout)");
  }
}

void DistributedTileService::beginFrame() {
  report_ = {};
  adoptChanges(++reportFrame_);
  startRows();
  costs_.nextFrame();
}

// Each server's report starts empty; a member, or one that left for this
// frame, gets a row.
void DistributedTileService::startRows() {
  rowOf_.assign(servers_.size(), -1);
  int rows = 0;
  for (std::size_t i = 0; i < servers_.size(); ++i) {
    ServerPool::Server& s = servers_[i];
    ServerReport fresh;
    fresh.address = s.address.name;
    fresh.state = s.report.state;
    fresh.why = s.report.why;
    fresh.joined = s.joinedFrame == reportFrame_;
    s.report = std::move(fresh);
    if (s.member || s.leftFrame == reportFrame_) rowOf_[i] = rows++;
  }
}

void DistributedTileService::startReport(Frame& frame) {
  if (rowOf_.size() != servers_.size()) startRows();  // render() without beginFrame(), or servers changed since
  frame.reportBase = report_.rects.size();
  for (const TileJob& job : frame.jobs) {
    report_.rects.push_back(job.rect);
    report_.masks.push_back(job.mask);
  }
  report_.deliveredBy.resize(report_.rects.size(), -1);
  for (const ServerPool::Server& s : servers_.all()) {
    frame.bytesIn.push_back(s.link->bytesReceived());
    frame.bytesOut.push_back(s.link->bytesSent());
  }
}

void DistributedTileService::finishReport(const Frame& frame) {
  report_.reissuedTiles += frame.dispatcher.reissued();
  report_.duplicatedTiles += frame.dispatcher.duplicated();
  report_.hedgedTiles += frame.dispatcher.hedged();
  report_.reissued.resize(report_.rects.size(), false);
  for (std::size_t t = 0; t < frame.sent.size(); ++t) {
    report_.reissued[frame.reportBase + frame.sent[t]] = frame.dispatcher.wasReissued(t);
  }
  report_.servers.clear();
  for (std::size_t i = 0; i < servers_.size(); ++i) {
    ServerPool::Server& s = servers_[i];
    if (rowOf_[i] < 0) continue;
    if (s.member && !s.link->ready() && !s.link->failed()) {
      s.report.state = ServerState::kUnreachable;
      s.report.why = "not ready yet (connecting, or receiving and building the scene)";
    }
    s.report.rttMs = std::max(0.0, paces_[i].rttMs);
    s.report.bytesIn += s.link->bytesReceived() - std::min(s.link->bytesReceived(), frame.bytesIn[i]);
    s.report.bytesOut += s.link->bytesSent() - std::min(s.link->bytesSent(), frame.bytesOut[i]);
    report_.servers.push_back(s.report);
  }
}

std::string DistributedTileService::tracedShares() const {
  if (!frame_ || frame_->traced == 0) return "";
  std::string shares;
  for (std::size_t i = 0; i < servers_.size(); ++i) {
    if (frame_->tracedBy[i] == 0) continue;
    if (!shares.empty()) shares += ", ";
    shares += servers_[i].address.name + " " + std::to_string(frame_->tracedBy[i] * 100 / frame_->traced) + " %";
  }
  return shares;
}

}  // namespace glint
