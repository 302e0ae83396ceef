// The tile costs the dispatcher balances by: traced pixels at first, then
// what the previous frame measured for the same tile, in the same unit.
#include "client/farm/tile_cost_model.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

std::vector<TileJob> twoTiles() { return {{{0, 0, 8, 8}, {}}, {{8, 0, 8, 4}, {}}}; }

TEST(TileCostModel, TracedPixelsUntilAFrameIsMeasured) {
  TileCostModel model;
  const std::vector<TileJob> jobs = twoTiles();
  EXPECT_EQ(model.costs(jobs, {0, 1}), (std::vector<double>{64.0, 32.0}));
  model.record(jobs[0], 64.0, 2.0);
  EXPECT_EQ(model.costs(jobs, {0, 1}), (std::vector<double>{64.0, 32.0}));  // until the next frame
}

TEST(TileCostModel, MeasuredTimesScaledIntoPixelsPriceTheNextFrame) {
  TileCostModel model;
  const std::vector<TileJob> jobs = twoTiles();
  model.record(jobs[0], 64.0, 1.0);  // 64 pixels in 1 ms
  model.record(jobs[1], 32.0, 3.0);  // 32 pixels in 3 ms: a costly tile (a mirror, say)
  model.nextFrame();
  // 96 pixels estimated took 4 ms: 24 pixels a ms.
  EXPECT_EQ(model.costs(jobs, {0, 1}), (std::vector<double>{24.0, 72.0}));
  // A tile of another shape was not measured: its pixels.
  const std::vector<TileJob> other{{{0, 0, 4, 4}, {}}};
  EXPECT_EQ(model.costs(other, {0}), (std::vector<double>{16.0}));
  model.nextFrame();  // nothing measured in between: back to pixels
  EXPECT_EQ(model.costs(jobs, {0, 1}), (std::vector<double>{64.0, 32.0}));
}

}  // namespace
}  // namespace glint
