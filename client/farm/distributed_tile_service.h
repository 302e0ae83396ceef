#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <asio.hpp>

#include "client/farm/distribution_report.h"
#include "client/farm/frame_run.h"
#include "client/farm/server_link.h"
#include "client/farm/server_list.h"
#include "client/farm/server_pool.h"
#include "client/farm/server_source.h"
#include "client/farm/tile_cost_model.h"
#include "common/render/tile_service.h"
#include "proto/scene_bundle.h"
#include "proto/tls.h"

namespace glint {

struct DistributedSettings {
  std::chrono::milliseconds stallTimeout{2000};  // --stall-timeout
  LinkTimeouts timeouts;
  proto::TlsFiles tls;  // --tls-ca, --tls-cert, --tls-key: every server over TLS 1.3
  // The constructor waits for one server to be ready (and throws when none
  // can be); glint view does not, and shows the raster frame meanwhile.
  bool awaitOne = true;
};

// The tile interface over one or many glintd: each server gets the scene by
// hash (all at once), and each frame's tiles flow to the servers that are
// ready, as the TileDispatcher decides. A server lost during a frame has its
// tiles reissued to the others, so the frame comes out byte-identical (one
// lost for breaking the protocol, its delivered tiles as well: results are
// held until the frame is whole, and done() called then); it is
// tried again on later frames, with backoff. All sockets run on one Asio
// io_context, driven by the thread that calls render(), which is also the
// thread that calls `done`: what a link tells (ready, a result, a failure)
// and a timer set for the dispatcher's next stall or hedge are its events,
// and each asks for the dispatcher's assignments to be sent. The farm may change between frames: the source
// is asked at each frame's start (and by refresh()), servers that join are
// connected, and used as soon as they hold the scene; servers that leave
// are told Goodbye (a frame in flight never loses one this way).
class DistributedTileService : public TileService, private LinkListener {
 public:
  // Connects to every server at once and returns when one is ready to
  // serve (settings.awaitOne). Throws InputError when none can: one line per
  // server saying why, or the scene's error (the same on every server).
  DistributedTileService(ServerSource servers, const proto::SceneBundle& bundle,
                         const DistributedSettings& settings = {});
  ~DistributedTileService() override;

  void render(const FrameSettings& frame, std::span<const TileJob> jobs,
              const std::function<void(std::size_t, TileOutput&&)>& done) override;
  // Fills an irradiance field over `bounds` for `frame` in batches of
  // probes the servers trace as tiles (the same dispatch, failover and
  // report; onTraced counts their probes): the same bytes as buildField in
  // process. Its report is fieldReport(). Throws InputError as render().
  IrradianceField fillField(const FrameSettings& frame, const Bounds3& bounds, const FieldSettings& settings);
  // Probes a batch of fillField holds.
  static constexpr int kBatchProbes = 64;
  // The field the frames rendered after read (path transport's light
  // between surfaces, as LocalTileService's), sent to every server that
  // serves now or later; it must outlive the service. nullptr: none.
  void useField(const IrradianceField* field);
  // Whether the frames rendered after read the field useField() gave (by
  // default they do); those that do not trace path transport in full.
  void readField(bool reads) { readsField_ = reads; }
  const DistributionReport& fieldReport() const { return fieldReport_; }
  int parallelism() const override;
  void beginFrame() override;

  // Waits until no server is still connecting or receiving the scene, or
  // `limit` passes (render does not: a frame starts on the servers ready).
  void awaitServers(std::chrono::milliseconds limit);
  // Between frames (glint view, idle): asks the source for changes, and lets
  // the links connect and upload meanwhile; the next frame reports them.
  void refresh();

  const DistributionReport& lastFrame() const { return report_; }
  std::size_t serversUp() const;
  // While a frame renders (from a progress callback): the share of its
  // results so far each server traced ("10.0.0.2:7878 40 %, ..."); "" when
  // none came yet.
  std::string tracedShares() const;
  // Members of the farm now.
  std::size_t serverCount() const { return servers_.members(); }
  // Sent the scene to at least one server (it did not hold it).
  bool uploaded() const;

 private:
  // LinkListener
  void linkReady(ServerLink& link) override;
  void linkResult(ServerLink& link, std::uint32_t frameId, std::uint32_t tileId, TileOutput&& out) override;
  void linkFailed(ServerLink& link, const LinkFailure& failure) override;

  void joinFrame(std::size_t index);
  // render()'s and fillField()'s frame: the jobs to the servers until every one is delivered.
  void run(const FrameSettings& settings, std::span<const TileJob> jobs,
           const std::function<void(std::size_t, TileOutput&&)>& done, const proto::FrameWork& work);
  // The source's changes to the pool; `frame`, the report that shows them.
  void adoptChanges(int frame);
  // Sends what the dispatcher assigns, soon (once, however many ask).
  void dispatchSoon();
  void dispatch();
  // Sets the timer for the dispatcher's next check; at it, stalled servers
  // are lost and what it assigns (hedged copies) is sent.
  void armChecks();
  void check(const asio::error_code& error);
  void throwIfHopeless();
  void deliverFrame(FrameRun& frame);
  void startRows();
  std::size_t startReport(std::span<const TileJob> jobs);
  void finishReport(const FrameRun& frame);
  double nowMs() const;

  asio::io_context io_;
  ServerSource source_;
  std::string warned_;  // the source's warning last printed
  proto::BundleDigest digest_;
  DistributedSettings settings_;
  ServerPool servers_;  // after io_, digest_ and settings_, which its links use
  std::chrono::steady_clock::time_point epoch_ = std::chrono::steady_clock::now();
  asio::steady_timer checks_{io_};
  bool dispatchPosted_ = false;
  std::uint32_t frameId_ = 0;
  std::unique_ptr<FrameRun> frame_;  // from render()'s start to its end; none between frames
  std::optional<std::string> sceneError_;
  TileCostModel costs_;
  DistributionReport report_;  // the frame since beginFrame(), every render() in it
  int reportFrame_ = 0;        // beginFrame() calls so far
  const IrradianceField* field_ = nullptr;  // useField()'s
  bool readsField_ = true;
  DistributionReport fieldReport_;           // fillField()'s
  std::size_t rowsFor_ = 0;    // the servers the report's rows were started for
};

}  // namespace glint
