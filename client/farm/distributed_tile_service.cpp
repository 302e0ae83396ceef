#include "client/farm/distributed_tile_service.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

#include "common/base/error.h"

namespace glint {
namespace {

constexpr std::chrono::seconds kGoodbyeGrace{1};  // for the Goodbyes to be written at the end

}  // namespace

DistributedTileService::DistributedTileService(ServerSource servers, const proto::SceneBundle& bundle,
                                               const DistributedSettings& settings)
    : source_(std::move(servers)),
      digest_(proto::digest(bundle)),
      settings_(settings),
      servers_(io_, source_.addresses(), bundle, digest_, settings.timeouts, settings.tls, *this) {
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
  if (changed) servers_.adopt(source_.addresses(), frame);
}

double DistributedTileService::nowMs() const {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - epoch_).count();
}

std::size_t DistributedTileService::serversUp() const {
  return servers_.up();
}

bool DistributedTileService::uploaded() const {
  return servers_.anyUploaded();
}

int DistributedTileService::parallelism() const {
  return std::max(1, servers_.threadsUp());
}

// No server serves the frame and none is still on its way: a server that
// answered Busy is tried again when its backoff ends, within the scene
// timeout of its first Busy; failing that, the frame fails, one line each.
void DistributedTileService::throwIfHopeless() {
  if (servers_.anyConnecting() || (frame_ ? frame_->dispatcher().liveServers() > 0 : serversUp() > 0)) return;
  const auto retry = servers_.nextBusyRetry(settings_.timeouts.scene);
  if (!retry) throw InputError("no glintd can serve this frame:" + servers_.states());
  const double seconds = std::chrono::duration<double>(*retry - std::chrono::steady_clock::now()).count();
  std::fprintf(stderr, "glint: every glintd is busy; trying again in %.0f s\n", std::max(0.0, seconds));
  std::this_thread::sleep_until(*retry);
  servers_.retryLost();
}

void DistributedTileService::linkReady(ServerLink& link) {
  servers_.ready(link.index());
  servers_[link.index()].pace.threads = link.threads();
  if (field_) link.sendField(*field_);
  if (frame_) joinFrame(link.index());
}

void DistributedTileService::useField(const IrradianceField* field) {
  field_ = field;
  if (!field_) return;
  for (std::size_t i = 0; i < servers_.size(); ++i) {
    if (servers_.serving(i)) servers_[i].link->sendField(*field_);
  }
}

IrradianceField DistributedTileService::fillField(const FrameSettings& frame, const Bounds3& bounds,
                                                  const FieldSettings& settings) {
  if (bounds.empty()) throw InputError("the irradiance field: the scene has no object to span");
  IrradianceField field(bounds, settings);
  std::vector<TileJob> batches;
  for (int first = 0; first < field.probeCount(); first += kBatchProbes) {
    batches.push_back({{first, 0, std::min(kBatchProbes, field.probeCount() - first), 1}, {}});
  }
  constexpr int kFloats = IrradianceField::kProbeFloats;
  beginFrame();
  run(frame, batches,
      [&](std::size_t j, TileOutput&& out) {
        const TileRect& r = batches[j].rect;
        for (int i = 0; i < r.width; ++i) {
          field.probe(r.x + i) = IrradianceField::readProbe(
              std::span<const float, kFloats>(out.probes.data() + static_cast<std::size_t>(i) * kFloats, kFloats));
        }
      },
      {settings, true});
  fieldReport_ = report_;
  return field;
}

void DistributedTileService::linkFailed(ServerLink& link, const LinkFailure& failure) {
  servers_.failed(link.index(), failure);
  if (failure.kind == LinkFailure::Kind::kSceneError && !sceneError_) {
    sceneError_ = "server " + servers_[link.index()].address.name + ": " + failure.what;
  }
  if (!frame_) return;
  TileDispatcher& dispatcher = frame_->dispatcher();
  if (!dispatcher.joined(link.index()) || dispatcher.lost(link.index())) return;
  if (failure.kind != LinkFailure::Kind::kBadBytes) {
    dispatcher.lose(link.index());
  } else {
    for (const std::size_t tile : dispatcher.distrust(link.index())) frame_->drop(tile);
    traced(frame_->heldWork());
  }
  dispatchSoon();
}

void DistributedTileService::joinFrame(std::size_t index) {
  FarmServer& s = servers_[index];
  s.link->setupFrame(frame_->id(), frame_->settings(), frame_->work());
  frame_->dispatcher().join(index, s.pace, nowMs());
  dispatchSoon();
}

void DistributedTileService::linkResult(ServerLink& link, std::uint32_t frameId, std::uint32_t tileId,
                                        TileOutput&& out) {
  if (!frame_ || frameId != frame_->id() || tileId >= frame_->tiles()) return;  // a cancelled copy, late
  const std::size_t index = link.index();
  const TileDispatcher::Delivery d = frame_->dispatcher().deliver(index, tileId, nowMs(), out.computeMs);
  if (!d.first) return;
  for (const std::size_t other : d.cancelOn) servers_[other].link->cancel(frameId, std::span(&tileId, 1));
  frame_->hold(tileId, index, std::move(out));
  traced(frame_->heldWork());
  dispatchSoon();
}

// The frame is whole: each result to the caller, and to the report.
void DistributedTileService::deliverFrame(FrameRun& frame) {
  frame.deliver([&](std::size_t job, std::size_t tile, std::size_t server, const TileOutput& out) {
    FarmServer& s = servers_[server];
    ++s.report.tiles;
    s.report.maskedPixels += out.rgb.size() / 3;
    s.report.probes += out.probes.size() / IrradianceField::kProbeFloats;
    s.report.rays += out.rays;
    s.report.busyMs += out.computeMs;
    report_.deliveredBy[frame.reportBase() + job] = s.reportRow;
    costs_.record(frame.job(tile), frame.dispatcher().cost(tile), out.computeMs);
  });
  for (std::size_t i = 0; i < servers_.size(); ++i) {
    if (frame.dispatcher().joined(i)) servers_[i].pace = frame.dispatcher().pace(i);
  }
}

void DistributedTileService::render(const FrameSettings& settings, std::span<const TileJob> jobs,
                                    const std::function<void(std::size_t, TileOutput&&)>& done) {
  proto::FrameWork work;
  if (field_ && readsField_) work.field = field_->settings();
  run(settings, jobs, done, work);
}

void DistributedTileService::run(const FrameSettings& settings, std::span<const TileJob> jobs,
                                 const std::function<void(std::size_t, TileOutput&&)>& done,
                                 const proto::FrameWork& work) {
  servers_.retryLost();
  std::vector<std::size_t> traced;
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    if (tracedPixels(jobs[j]) > 0) {
      traced.push_back(j);
    } else {
      done(j, TileOutput{});
    }
  }
  DispatchSettings dispatch;
  dispatch.stallTimeoutMs = static_cast<double>(settings_.stallTimeout.count());
  const std::size_t reportBase = startReport(jobs);
  std::vector<double> costs = costs_.costs(jobs, traced);
  frame_ = std::make_unique<FrameRun>(++frameId_, settings, work, jobs, done, std::move(traced), std::move(costs),
                                      servers_.size(), dispatch, reportBase);
  struct EndOfFrame {  // however render() ends
    std::unique_ptr<FrameRun>& frame;
    asio::steady_timer& checks;
    ~EndOfFrame() {
      checks.cancel();
      frame.reset();
    }
  } end{frame_, checks_};
  FrameRun& frame = *frame_;
  try {
    for (std::size_t i = 0; i < servers_.size(); ++i) {
      if (servers_.serving(i)) joinFrame(i);
    }
    while (!frame.dispatcher().done()) {
      if (sceneError_) throw InputError(*sceneError_);
      throwIfHopeless();
      if (io_.stopped()) io_.restart();
      io_.run_one();
    }
  } catch (...) {
    for (FarmServer& s : servers_.all()) s.link->cancel(frame.id(), {});
    throw;
  }
  frame.dispatcher().finish();
  deliverFrame(frame);
  finishReport(frame);
}

void DistributedTileService::dispatchSoon() {
  if (dispatchPosted_) return;
  dispatchPosted_ = true;
  asio::post(io_, [this] {
    dispatchPosted_ = false;
    dispatch();
  });
}

void DistributedTileService::dispatch() {
  if (!frame_) return;
  FrameRun& f = *frame_;
  for (const TileDispatcher::Assignment& a : f.dispatcher().assign(nowMs())) {
    servers_[a.server].link->request(f.id(), static_cast<std::uint32_t>(a.tile), f.job(a.tile));
  }
  armChecks();
}

void DistributedTileService::armChecks() {
  const double at = frame_->dispatcher().nextCheck(nowMs());
  if (!std::isfinite(at)) {
    checks_.cancel();
    return;
  }
  // Just past the moment: the dispatcher's conditions hold after it.
  checks_.expires_at(epoch_ +
                     std::chrono::ceil<std::chrono::nanoseconds>(std::chrono::duration<double, std::milli>(at)) +
                     std::chrono::nanoseconds(1));
  checks_.async_wait([this](const asio::error_code& error) { check(error); });
}

void DistributedTileService::check(const asio::error_code& error) {
  if (error || !frame_) return;
  for (const std::size_t s : frame_->dispatcher().stalled(nowMs())) {
    servers_[s].link->fail(LinkFailure::Kind::kStalled, "stalled: delivered nothing for " +
                                                            std::to_string(settings_.stallTimeout.count()) +
                                                            " ms with tiles outstanding (--stall-timeout)");
  }
  dispatch();
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
  int rows = 0;
  for (FarmServer& s : servers_.all()) {
    ServerReport fresh;
    fresh.address = s.address.name;
    fresh.state = s.report.state;
    fresh.why = s.report.why;
    fresh.joined = s.joinedFrame == reportFrame_;
    s.report = std::move(fresh);
    s.reportRow = s.member || s.leftFrame == reportFrame_ ? rows++ : -1;
  }
  rowsFor_ = servers_.size();
}

// The render()'s jobs join the report (returns the index of the first), and
// each link's counters are noted.
std::size_t DistributedTileService::startReport(std::span<const TileJob> jobs) {
  if (rowsFor_ != servers_.size()) startRows();  // render() without beginFrame(), or servers changed since
  const std::size_t base = report_.rects.size();
  for (const TileJob& job : jobs) {
    report_.rects.push_back(job.rect);
    report_.masks.push_back(job.mask);
  }
  report_.deliveredBy.resize(report_.rects.size(), -1);
  for (FarmServer& s : servers_.all()) {
    s.bytesInAtStart = s.link->bytesReceived();
    s.bytesOutAtStart = s.link->bytesSent();
  }
  return base;
}

void DistributedTileService::finishReport(const FrameRun& frame) {
  report_.reissuedTiles += frame.dispatcher().reissued();
  report_.duplicatedTiles += frame.dispatcher().duplicated();
  report_.hedgedTiles += frame.dispatcher().hedged();
  report_.reissued.resize(report_.rects.size(), false);
  for (std::size_t t = 0; t < frame.tiles(); ++t) {
    report_.reissued[frame.reportBase() + frame.jobIndex(t)] = frame.dispatcher().wasReissued(t);
  }
  report_.servers.clear();
  for (FarmServer& s : servers_.all()) {
    if (s.reportRow < 0) continue;
    if (s.member && !s.link->ready() && !s.link->failed()) {
      s.report.state = ServerState::kUnreachable;
      s.report.why = "not ready yet (connecting, or receiving and building the scene)";
    }
    s.report.rttMs = std::max(0.0, s.pace.rttMs);
    s.report.bytesIn += s.link->bytesReceived() - std::min(s.link->bytesReceived(), s.bytesInAtStart);
    s.report.bytesOut += s.link->bytesSent() - std::min(s.link->bytesSent(), s.bytesOutAtStart);
    report_.servers.push_back(s.report);
  }
}

std::string DistributedTileService::tracedShares() const {
  if (!frame_ || frame_->held() == 0) return "";
  std::string shares;
  for (std::size_t i = 0; i < servers_.size(); ++i) {
    const std::size_t held = frame_->heldFrom(i);
    if (held == 0) continue;
    if (!shares.empty()) shares += ", ";
    shares += servers_[i].address.name + " " + std::to_string(held * 100 / frame_->held()) + " %";
  }
  return shares;
}

}  // namespace glint
