// The adaptive patterns: one sample per pixel, the full jittered count where
// a pixel differs from a neighbour (adaptive: a channel by a threshold;
// perceptual: visibly, by FLIP's colour term). Deterministic whatever the
// threads and tiles; cheap where the image is flat; the jittered image where
// every pixel is an edge; each perceptual pixel either the centre ray or
// the jittered pixel.
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

TEST(PerceptualSampling, SameImageForAnyThreadsAndTiles) {
  Scene scene = room(SamplePattern::kPerceptual, 1.0f / 64.0f);
  const FrameResult first = test::render(scene, 1, 96);
  for (const auto& [threads, tile] : {std::pair{2, 8}, {3, 13}, {2, 64}, {1, 1}}) {
    EXPECT_EQ(test::render(scene, threads, tile).image.rgb, first.image.rgb) << threads << " threads, tile " << tile;
  }
  const auto pixels = static_cast<std::uint64_t>(96 * 72);
  EXPECT_GT(first.stats.primary, pixels);
  EXPECT_LT(first.stats.primary, 16 * pixels / 2);
}

// Every pixel is either the ray through its centre (the regular pattern's
// one sample) or, refined, the jittered pattern's pixel; both occur, and
// the rays are one a pixel plus the jittered count for each refined one.
TEST(PerceptualSampling, EachPixelIsTheCentreRayOrTheJitteredPixel) {
  Scene scene = room(SamplePattern::kPerceptual, 1.0f / 64.0f);
  const FrameResult perceptual = test::render(scene, 2, 96);
  scene.frame.sampling.pattern = SamplePattern::kJittered;
  const FrameResult jittered = test::render(scene, 2, 96);
  scene.frame.sampling.pattern = SamplePattern::kRegular;
  scene.frame.sampling.samples = 1;
  const FrameResult centre = test::render(scene, 2, 96);
  std::uint64_t refined = 0, unrefined = 0;
  for (std::size_t p = 0; p < perceptual.image.rgb.size(); p += 3) {
    const auto same = [&](const FrameImage& other) {
      return std::equal(other.rgb.begin() + static_cast<std::ptrdiff_t>(p),
                        other.rgb.begin() + static_cast<std::ptrdiff_t>(p + 3),
                        perceptual.image.rgb.begin() + static_cast<std::ptrdiff_t>(p));
    };
    const bool isCentre = same(centre.image), isJittered = same(jittered.image);
    ASSERT_TRUE(isCentre || isJittered) << "pixel " << p / 3;
    refined += isJittered && !isCentre ? 1 : 0;
    unrefined += isCentre && !isJittered ? 1 : 0;
  }
  EXPECT_GT(refined, 100u);
  EXPECT_GT(unrefined, 500u);
  EXPECT_GE(perceptual.stats.primary, 96u * 72u + 16u * refined);
}

// Two flat halves, the left a colour, the right another: the pixels along
// the seam are refined only when the two differ visibly.
Scene halves(const char* right, float threshold) {
  Scene scene = test::sceneFromJson(std::string(R"({"glint": 1, "image": {"width": 40, "height": 30},
      "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, "background": )") + right + R"(,
      "sampling": {"pattern": "perceptual", "samples": 16},
      "materials": {"left": {"color": [0, 0, 0], "ambient": 0, "diffuse": 0, "emission": [0.5, 0.5, 0.5]}},
      "objects": [{"type": "quad", "corners": [[-50, -50, 0], [0.01, -50, 0], [0.01, 50, 0], [-50, 50, 0]],
                   "material": "left"}]})");
  scene.frame.sampling.perceptualThreshold = threshold;
  return scene;
}

TEST(PerceptualSampling, OnlyAVisibleDifferenceIsRefined) {
  const std::uint64_t pixels = 40u * 30u;
  // 0.5 against 0.51 (8-bit 128 and 130, through sRGB): under a just
  // noticeable difference, FLIP's colour term about 0.04.
  EXPECT_EQ(test::render(halves("[0.51, 0.51, 0.51]", 0.3f), 2, 64).stats.primary, pixels);
  // 0.5 against 0.1: plainly visible; the seam's two columns take 16 samples.
  const FrameResult seen = test::render(halves("[0.1, 0.1, 0.1]", 0.3f), 2, 64);
  EXPECT_EQ(seen.stats.primary, pixels + 2u * 30u * 16u);
  // The same faint seam is refined at a threshold below its difference.
  EXPECT_EQ(test::render(halves("[0.51, 0.51, 0.51]", 0.02f), 2, 64).stats.primary, pixels + 2u * 30u * 16u);
}

TEST(AdaptiveSampling, TheThresholdIsChecked) {
  EXPECT_THROW(test::sceneFromJson(R"({"glint": 1, "image": {"width": 4, "height": 4},
      "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
      "sampling": {"pattern": "adaptive", "adaptive_threshold": 0}, "objects": []})"),
               InputError);
  EXPECT_THROW(test::sceneFromJson(R"({"glint": 1, "image": {"width": 4, "height": 4},
      "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
      "sampling": {"pattern": "perceptual", "perceptual_threshold": 1.5}, "objects": []})"),
               InputError);
}

}  // namespace
}  // namespace glint
