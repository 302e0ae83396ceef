#include "common/render/frame.h"

#include <gtest/gtest.h>

#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

Scene smallRoom() {
  Scene s = loadSceneFile(test::sourcePath("scenes/room.json"));
  s.frame.width = 160;
  s.frame.height = 120;
  return s;
}

// The same scene gives byte-identical images whatever the thread count and
// the tile split.
TEST(Frame, ImageIndependentOfThreadsAndTiles) {
  const Scene s = smallRoom();
  const FrameResult a = test::render(s, 1, 32);
  const FrameResult b = test::render(s, 2, 7);
  const FrameResult c = test::render(s, 2, 200);
  EXPECT_EQ(a.image.rgb, b.image.rgb);
  EXPECT_EQ(a.image.rgb, c.image.rgb);
  EXPECT_EQ(a.stats.total(), b.stats.total());
  EXPECT_EQ(a.stats.primary, 160u * 120u * 4u);
}

TEST(Frame, SeedChangesTheJitterOnly) {
  Scene s = smallRoom();
  const FrameResult a = test::render(s, 2);
  s.frame.sampling.seed = 99;
  const FrameResult b = test::render(s, 2);
  EXPECT_NE(a.image.rgb, b.image.rgb);
  std::size_t close = 0;
  for (std::size_t i = 0; i < a.image.rgb.size(); ++i) close += std::abs(a.image.rgb[i] - b.image.rgb[i]) <= 40;
  EXPECT_GT(close, a.image.rgb.size() * 95 / 100);
}

// A masked tile returns exactly the masked pixels of the full frame, in scan order.
TEST(Frame, MaskedTileEqualsFullFramePixels) {
  const Scene s = smallRoom();
  const FrameResult full = test::render(s, 2);
  const PreparedScene prepared(s, BvhSettings{});
  const Renderer renderer(prepared, s.frame);
  const TileRect rect{37, 21, 19, 13};
  std::vector<std::uint8_t> mask(maskByteCount(rect), 0);
  for (std::size_t i = 0; i < rect.pixelCount(); i += 3) setMaskBit(mask, i);
  std::vector<std::uint8_t> rgb;
  RayStats stats;
  renderer.renderTile(rect, mask, rgb, stats);
  ASSERT_EQ(rgb.size(), countMasked(rect, mask) * 3);
  std::size_t k = 0;
  for (std::size_t i = 0; i < rect.pixelCount(); ++i) {
    if (!maskBit(mask, i)) continue;
    const int x = rect.x + static_cast<int>(i) % rect.width;
    const int y = rect.y + static_cast<int>(i) / rect.width;
    const test::Rgb p = test::pixelAt(full.image, x, y);
    EXPECT_EQ(rgb[k], p.r);
    EXPECT_EQ(rgb[k + 1], p.g);
    EXPECT_EQ(rgb[k + 2], p.b);
    k += 3;
  }
  EXPECT_EQ(stats.primary, countMasked(rect, mask) * 4);
}

TEST(Frame, TileGridCoversTheImageOnce) {
  const auto tiles = tileGrid(100, 37, 16);
  std::vector<int> covered(100 * 37, 0);
  for (const TileRect& t : tiles) {
    for (int y = t.y; y < t.y + t.height; ++y) {
      for (int x = t.x; x < t.x + t.width; ++x) ++covered[static_cast<std::size_t>(y * 100 + x)];
    }
  }
  for (int c : covered) ASSERT_EQ(c, 1);
}

TEST(Frame, WorkerExceptionsReachTheCaller) {
  ThreadPool pool(2);
  EXPECT_THROW(pool.parallelFor(100, [](std::size_t i) {
    if (i == 57) throw std::runtime_error("boom");
  }),
               std::runtime_error);
  int sum = 0;
  std::mutex m;
  pool.parallelFor(10, [&](std::size_t i) {
    std::lock_guard lock(m);
    sum += static_cast<int>(i);
  });
  EXPECT_EQ(sum, 45);  // the pool still works after a failure
}

}  // namespace
}  // namespace glint
