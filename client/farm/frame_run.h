#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "client/farm/tile_dispatcher.h"
#include "common/render/tile_service.h"
#include "proto/messages.h"

namespace glint {

// One render() call on the farm: the jobs with pixels to trace (the
// dispatcher's tiles, each priced), the dispatcher's frame, and the results
// held until the frame is whole, each with the server it came from (a
// server caught lying has its own dropped).
class FrameRun {
 public:
  using Done = std::function<void(std::size_t, TileOutput&&)>;

  // `work` what the jobs are (pixels, or a field's probes); `traced` the
  // indices of `jobs` with pixels to trace, `costs` their prices; `servers`
  // the farm's records (the dispatcher's key); `reportBase` the report's
  // index of jobs[0].
  FrameRun(std::uint32_t id, const FrameSettings& settings, const proto::FrameWork& work, std::span<const TileJob> jobs,
           const Done& done, std::vector<std::size_t> traced, std::vector<double> costs, std::size_t servers,
           const DispatchSettings& dispatch, std::size_t reportBase);
  FrameRun(const FrameRun&) = delete;
  FrameRun& operator=(const FrameRun&) = delete;

  std::uint32_t id() const { return id_; }
  const FrameSettings& settings() const { return settings_; }
  const proto::FrameWork& work() const { return work_; }
  TileDispatcher& dispatcher() { return dispatcher_; }
  const TileDispatcher& dispatcher() const { return dispatcher_; }
  std::size_t tiles() const { return jobOf_.size(); }
  std::size_t jobIndex(std::size_t tile) const { return jobOf_[tile]; }
  const TileJob& job(std::size_t tile) const { return jobs_[jobOf_[tile]]; }
  std::size_t reportBase() const { return reportBase_; }

  // The first result of `tile` arrived, from `server`.
  void hold(std::size_t tile, std::size_t server, TileOutput&& out);
  // Drops the result held for `tile`, if one is.
  void drop(std::size_t tile);
  std::size_t held() const { return held_; }
  // The pixels (or a field's probes) those results hold.
  std::size_t heldWork() const { return heldWork_; }
  // Of those, how many came from `server`.
  std::size_t heldFrom(std::size_t server) const { return heldFrom_[server]; }

  // The frame is whole: for each tile in order, `each(job, tile, server,
  // result)` (the report's bookkeeping), then the result to render()'s caller.
  void deliver(
      const std::function<void(std::size_t job, std::size_t tile, std::size_t server, const TileOutput&)>& each);

 private:
  std::uint32_t id_;
  const FrameSettings& settings_;
  proto::FrameWork work_;
  std::span<const TileJob> jobs_;
  const Done& done_;
  std::vector<std::size_t> jobOf_;  // the dispatcher's tile -> the job's index
  TileDispatcher dispatcher_;
  std::vector<std::optional<TileOutput>> outputs_;  // by tile
  std::vector<std::size_t> from_;                   // by tile: the server of the held result
  std::size_t held_ = 0;
  std::size_t heldWork_ = 0;
  std::vector<std::size_t> heldFrom_;  // by server
  std::size_t reportBase_;
};

}  // namespace glint
