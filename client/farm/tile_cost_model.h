#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "common/render/tile_service.h"

namespace glint {

// What each tile of a frame will cost to trace, in the dispatcher's units:
// its traced pixels, or, where the previous frame measured the same tile
// (same rectangle, same count of masked pixels), its tracing time then,
// scaled into pixels by the ratio of all such estimates to their times.
// Costs steer the dispatch only; they never change a pixel.
class TileCostModel {
 public:
  // The cost of each job the dispatcher gets (`sent`: indices into `jobs`).
  std::vector<double> costs(std::span<const TileJob> jobs, const std::vector<std::size_t>& sent) const;
  // A tile of this frame took `ms` to trace; it was estimated at `estimate`.
  void record(const TileJob& job, double estimate, double ms);
  // A new frame: what this one measured becomes what the next is priced by.
  void nextFrame();

 private:
  using Key = std::array<int, 5>;  // x, y, width, height, masked pixels
  using Times = std::map<Key, std::pair<double, double>>;  // estimate, measured ms
  static Key keyOf(const TileJob& job);

  Times last_;     // the previous frame's
  Times current_;  // this frame's so far
};

}  // namespace glint
