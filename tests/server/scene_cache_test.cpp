#include "server/scene_cache.h"

#include <gtest/gtest.h>

#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint::server {
namespace {

proto::SceneHash hashOf(std::uint8_t n) {
  proto::SceneHash h{};
  h[0] = n;
  return h;
}

std::shared_ptr<const PreparedScene> room() {
  return std::make_shared<const PreparedScene>(loadSceneFile(test::sourcePath("scenes/room.json")), BvhSettings{});
}

TEST(SceneCache, FindsWhatWasInserted) {
  SceneCache cache(std::size_t{1} << 30);
  EXPECT_EQ(cache.find(hashOf(1)), nullptr);
  const auto scene = room();
  cache.insert(hashOf(1), scene);
  EXPECT_EQ(cache.find(hashOf(1)), scene);
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_GE(cache.bytes(), memoryFootprint(*scene));
}

// Over the memory bound, the least recently used scene goes first; a scene
// still in use stays alive through its shared_ptr.
TEST(SceneCache, EvictsTheLeastRecentlyUsed) {
  const auto a = room(), b = room(), c = room();
  const std::size_t one = memoryFootprint(*a);
  SceneCache cache(2 * one + one / 2);  // room for two
  cache.insert(hashOf(1), a);
  cache.insert(hashOf(2), b);
  EXPECT_NE(cache.find(hashOf(1)), nullptr);  // 1 is now more recent than 2
  cache.insert(hashOf(3), c);
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_NE(cache.find(hashOf(1)), nullptr);
  EXPECT_EQ(cache.find(hashOf(2)), nullptr);
  EXPECT_NE(cache.find(hashOf(3)), nullptr);
  EXPECT_EQ(b->scene().frame.width, 640);  // evicted, still usable by whoever holds it

  SceneCache tiny(1);  // smaller than any scene: keeps just the newest
  tiny.insert(hashOf(1), a);
  tiny.insert(hashOf(2), b);
  EXPECT_EQ(tiny.size(), 1u);
  EXPECT_NE(tiny.find(hashOf(2)), nullptr);
}

}  // namespace
}  // namespace glint::server
