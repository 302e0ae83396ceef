// A frame summed in passes ends as the frame rendered at once, byte for
// byte, for either pattern and any tiles; a cancelled pass says so.
#include <gtest/gtest.h>

#include "common/render/frame.h"
#include "common/render/prepared_scene.h"
#include "common/render/progressive_frame.h"
#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

// A lit, glossy and diffuse scene, path traced: every sample draws many
// random numbers, so a pass that summed out of order would show.
Scene boxScene(const char* pattern, int samples) {
  const std::string text = std::string(R"({"glint": 1, "image": {"width": 40, "height": 24},
    "camera": {"eye": [0, 1, 4], "look_at": [0, 0.5, 0], "fov_y": 50},
    "sampling": {"pattern": ")") + pattern + R"(", "samples": )" + std::to_string(samples) + R"(},
    "tracing": {"transport": "path", "max_bounces": 4},
    "lights": [{"type": "area", "position": [0, 3, 0], "u": [1, 0, 0], "v": [0, 0, 1], "color": [4, 4, 4]}],
    "materials": {"white": {"color": [0.8, 0.8, 0.8]}, "gold": {"color": [0.9, 0.7, 0.3], "diffuse": 0.2,
                  "reflectivity": 0.8, "roughness": 0.3}},
    "objects": [{"type": "quad", "corners": [[-3, 0, 3], [3, 0, 3], [3, 0, -3], [-3, 0, -3]], "material": "white"},
                {"type": "sphere", "center": [0, 0.7, 0], "radius": 0.7, "material": "gold"}]})";
  return test::sceneFromJson(text);
}

TEST(ProgressiveFrame, ItsPassesEndAsTheFrameRenderedAtOnce) {
  for (const auto& [pattern, samples] : {std::pair{"jittered", 9}, std::pair{"regular", 16}}) {
    const Scene scene = boxScene(pattern, samples);
    const PreparedScene prepared(scene, BvhSettings{});
    const Renderer renderer(prepared, scene.frame);
    ThreadPool pool(2);
    const FrameResult atOnce = renderFrame(renderer, pool, FrameOptions{});
    ProgressiveFrame progressive(renderer, 7);
    std::vector<int> counts;
    while (!progressive.complete()) {
      ASSERT_TRUE(progressive.addPass(pool));
      counts.push_back(progressive.samples());
      if (!progressive.complete()) {
        EXPECT_NE(progressive.image().rgb, atOnce.image.rgb) << pattern;
      }
    }
    const std::vector<int> doubling = samples == 9 ? std::vector{1, 2, 4, 8, 9} : std::vector{1, 2, 4, 8, 16};
    EXPECT_EQ(counts, doubling) << pattern;
    EXPECT_EQ(progressive.image().rgb, atOnce.image.rgb) << pattern;
    EXPECT_EQ(progressive.stats().primary, atOnce.stats.primary) << pattern;
  }
}

TEST(ProgressiveFrame, ACancelledPassSaysSoAndTheAdaptivePatternsAreRefused) {
  const Scene scene = boxScene("jittered", 4);
  const PreparedScene prepared(scene, BvhSettings{});
  const Renderer renderer(prepared, scene.frame);
  ThreadPool pool(2);
  ProgressiveFrame progressive(renderer, 8);
  EXPECT_FALSE(progressive.addPass(pool, [] { return true; }));
  EXPECT_EQ(progressive.samples(), 0);

  Scene adaptive = boxScene("adaptive", 4);
  const PreparedScene preparedAdaptive(adaptive, BvhSettings{});
  const Renderer adaptiveRenderer(preparedAdaptive, adaptive.frame);
  EXPECT_THROW(ProgressiveFrame(adaptiveRenderer, 8), std::logic_error);
}

}  // namespace
}  // namespace glint
