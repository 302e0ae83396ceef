#include "client/farm/frame_run.h"

#include "common/render/irradiance_field.h"

namespace glint {

FrameRun::FrameRun(std::uint32_t id, const FrameSettings& settings, const proto::FrameWork& work,
                   std::span<const TileJob> jobs, const Done& done, std::vector<std::size_t> traced,
                   std::vector<double> costs, std::size_t servers, const DispatchSettings& dispatch,
                   std::size_t reportBase)
    : id_(id),
      settings_(settings),
      work_(work),
      jobs_(jobs),
      done_(done),
      jobOf_(std::move(traced)),
      dispatcher_(std::move(costs), servers, dispatch),
      outputs_(jobOf_.size()),
      from_(jobOf_.size()),
      heldFrom_(servers),
      reportBase_(reportBase) {}

namespace {

// The pixels a tile's result holds, or the probes a field's batch's does.
std::size_t workIn(const TileOutput& out) { return out.rgb.size() / 3 + out.probes.size() / IrradianceField::kProbeFloats; }

}  // namespace

void FrameRun::hold(std::size_t tile, std::size_t server, TileOutput&& out) {
  heldWork_ += workIn(out);
  outputs_[tile] = std::move(out);
  from_[tile] = server;
  ++held_;
  ++heldFrom_[server];
}

void FrameRun::drop(std::size_t tile) {
  if (!outputs_[tile]) return;
  heldWork_ -= workIn(*outputs_[tile]);
  outputs_[tile].reset();
  --held_;
  --heldFrom_[from_[tile]];
}

void FrameRun::deliver(
    const std::function<void(std::size_t job, std::size_t tile, std::size_t server, const TileOutput&)>& each) {
  for (std::size_t tile = 0; tile < jobOf_.size(); ++tile) {
    const std::size_t job = jobOf_[tile];
    each(job, tile, from_[tile], *outputs_[tile]);
    done_(job, std::move(*outputs_[tile]));
  }
}

}  // namespace glint
