#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <asio.hpp>

#include "client/distribution_report.h"
#include "client/server_link.h"
#include "client/server_list.h"
#include "client/server_pool.h"
#include "client/server_source.h"
#include "client/tile_cost_model.h"
#include "client/tile_dispatcher.h"
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
// thread that calls `done`. The farm may change between frames: the source
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
  struct Frame;  // the frame being rendered

  // LinkListener
  void linkReady(ServerLink& link) override;
  void linkResult(ServerLink& link, std::uint32_t frameId, std::uint32_t tileId, TileOutput&& out) override;
  void linkFailed(ServerLink& link, const LinkFailure& failure) override;

  void joinFrame(std::size_t index);
  // The source's changes to the pool; `frame`, the report that shows them.
  void adoptChanges(int frame);
  // Runs the I/O context for a moment, then loses stalled servers and sends
  // what the dispatcher assigns.
  void step();
  void throwIfHopeless();
  void deliverFrame(Frame& frame);
  void startRows();
  void startReport(Frame& frame);
  void finishReport(const Frame& frame);
  double nowMs() const;

  asio::io_context io_;
  ServerSource source_;
  std::string warned_;  // the source's warning last printed
  std::vector<ServerPace> paces_;
  proto::BundleDigest digest_;
  DistributedSettings settings_;
  ServerPool servers_;  // after io_, digest_ and settings_, which its links use
  std::chrono::steady_clock::time_point epoch_ = std::chrono::steady_clock::now();
  std::uint32_t frameId_ = 0;
  std::unique_ptr<Frame> frame_;  // from render()'s start to its end; none between frames
  std::optional<std::string> sceneError_;
  TileCostModel costs_;
  DistributionReport report_;  // the frame since beginFrame(), every render() in it
  int reportFrame_ = 0;        // beginFrame() calls so far
  std::vector<int> rowOf_;     // per server: its row in report_.servers, -1 for none
};

}  // namespace glint
