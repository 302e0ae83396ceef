// The adaptive pattern: one sample per pixel, the full jittered count where a
// pixel differs from a neighbour. Deterministic whatever the threads and
// tiles; cheap where the image is flat; the jittered image where every pixel
// is an edge.
#include <gtest/gtest.h>

#include "common/base/error.h"
#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

Scene room(SamplePattern pattern, float threshold) {
  Scene scene = loadSceneFile(test::sourcePath("scenes/room.json"));
  scene.frame.width = 96;
  scene.frame.height = 72;
  scene.frame.sampling.pattern = pattern;
  scene.frame.sampling.samples = 16;
  scene.frame.sampling.adaptiveThreshold = threshold;
  return scene;
}

TEST(AdaptiveSampling, SameImageForAnyThreadsAndTiles) {
  const Scene scene = room(SamplePattern::kAdaptive, 1.0f / 64.0f);
  const FrameResult first = test::render(scene, 1, 96);
  for (const auto& [threads, tile] : {std::pair{2, 8}, {3, 13}, {2, 64}, {1, 1}}) {
    EXPECT_EQ(test::render(scene, threads, tile).image.rgb, first.image.rgb) << threads << " threads, tile " << tile;
  }
  // It refines somewhere and not everywhere.
  const auto pixels = static_cast<std::uint64_t>(96 * 72);
  EXPECT_GT(first.stats.primary, pixels);
  EXPECT_LT(first.stats.primary, 16 * pixels);
}

TEST(AdaptiveSampling, AFlatImageTakesOneSampleAPixel) {
  Scene flat = test::sceneFromJson(R"({"glint": 1, "image": {"width": 40, "height": 30},
      "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, "background": [0.2, 0.4, 0.6],
      "sampling": {"pattern": "adaptive", "samples": 16}, "objects": []})");
  const FrameResult r = test::render(flat, 2, 64);  // one tile: no border pixels to trace
  EXPECT_EQ(r.stats.primary, 40u * 30u);
  const FrameResult tiled = test::render(flat, 2, 8);
  EXPECT_LT(tiled.stats.primary, 16u * 40u * 30u);  // borders cost a little; refinement nothing
  EXPECT_EQ(tiled.image.rgb, r.image.rgb);
}

// A wall lit by a close light with fall-off: no two pixels' first samples
// are alike, so with a tiny threshold every pixel is refined, and the image
// and its rays are the jittered pattern's.
Scene litWall(const char* pattern) {
  return test::sceneFromJson(std::string(R"({"glint": 1, "image": {"width": 48, "height": 36},
      "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "fov_y": 40},
      "sampling": {"pattern": ")") + pattern + R"(", "samples": 9, "adaptive_threshold": 1e-9},
      "materials": {"wall": {"color": [0.8, 0.7, 0.6], "ambient": 0.05, "diffuse": 0.9}},
      "lights": [{"type": "point", "position": [0.3, 0.2, 1.5], "color": [1, 1, 1], "attenuation": [0.2, 0.3, 0.5]}],
      "objects": [{"type": "quad", "corners": [[-5, -5, 0], [5, -5, 0], [5, 5, 0], [-5, 5, 0]], "material": "wall"}]})");
}

TEST(AdaptiveSampling, EveryPixelAnEdgeIsTheJitteredImage) {
  const FrameResult adaptive = test::render(litWall("adaptive"), 2, 48);
  const FrameResult jittered = test::render(litWall("jittered"), 2, 48);
  EXPECT_EQ(adaptive.image.rgb, jittered.image.rgb);
  EXPECT_EQ(adaptive.stats.primary, jittered.stats.primary);
  EXPECT_EQ(adaptive.stats.total(), jittered.stats.total());
}

TEST(AdaptiveSampling, TheThresholdIsChecked) {
  EXPECT_THROW(test::sceneFromJson(R"({"glint": 1, "image": {"width": 4, "height": 4},
      "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
      "sampling": {"pattern": "adaptive", "adaptive_threshold": 0}, "objects": []})"),
               InputError);
}

}  // namespace
}  // namespace glint
