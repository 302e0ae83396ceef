// The thin lens: a small self-lit sphere out of focus spreads over the
// circle of confusion (the spread's second moment is the disc's plus the
// sphere's own) and keeps its light; at the focus distance it stays sharp.
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/base/thread_pool.h"
#include "common/render/linear_frame.h"
#include "common/render/prepared_scene.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;
constexpr int kSize = 96;
constexpr double kFovY = 30.0;
constexpr double kRadius = 0.2;

Scene lensScene(double sphereDistance, double aperture, double focus) {
  json camera = {{"eye", {0, 0, 0}}, {"look_at", {0, 0, -1}}, {"fov_y", kFovY}};
  if (aperture > 0.0) {
    camera["aperture"] = aperture;
    camera["focus_distance"] = focus;
  }
  const json j = {{"glint", 1},
                  {"image", {{"width", kSize}, {"height", kSize}}},
                  {"camera", camera},
                  {"sampling", {{"pattern", "jittered"}, {"samples", 256}}},
                  {"materials", {{"glow", {{"emission", {1, 1, 1}}, {"diffuse", 0}}}}},
                  {"objects", {{{"type", "sphere"}, {"center", {0, 0, -sphereDistance}}, {"radius", kRadius},
                                {"material", "glow"}}}}};
  return test::sceneFromJson(j.dump());
}

struct Spread {
  double sum = 0.0;
  double meanSquareRadius = 0.0;  // intensity-weighted, about the image's centroid, in pixels^2
};

Spread spreadOf(const Scene& scene) {
  const PreparedScene prepared(scene, BvhSettings{});
  const Renderer renderer(prepared, scene.frame);
  ThreadPool pool(2);
  RayStats stats;
  const LinearImage image = renderLinear(renderer, pool, stats, LinearRange::kUnbounded);
  Spread s;
  double cx = 0.0, cy = 0.0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const double v = image.rgb[(static_cast<std::size_t>(y) * kSize + x) * 3];
      s.sum += v;
      cx += v * (x + 0.5);
      cy += v * (y + 0.5);
    }
  }
  cx /= s.sum;
  cy /= s.sum;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const double v = image.rgb[(static_cast<std::size_t>(y) * kSize + x) * 3];
      s.meanSquareRadius += v * ((x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy));
    }
  }
  s.meanSquareRadius /= s.sum;
  return s;
}

// A pixel's size at distance d, in scene units.
double pixelAt(double d) { return 2.0 * d * std::tan(kFovY * M_PI / 360.0) / kSize; }

TEST(DepthOfField, OutOfFocusSphereSpreadsOverTheCircleOfConfusion) {
  const double distance = 8.0, focus = 4.0, aperture = 0.5;
  const Spread pinhole = spreadOf(lensScene(distance, 0.0, 0.0));
  const Spread lens = spreadOf(lensScene(distance, aperture, focus));
  const double circle = aperture * std::abs(distance - focus) / distance / pixelAt(focus);  // diameter, pixels
  const double sphere = kRadius / pixelAt(distance);                                          // the image's radius
  // A uniform disc of radius R has a mean square radius of R^2 / 2; spreads add.
  const double expected = pinhole.meanSquareRadius + 0.25 * circle * circle / 2.0;
  std::printf("circle of confusion %.2f px, sphere %.2f px: mean square radius %.3f (pinhole %.3f, expected %.3f)\n",
              circle, sphere, lens.meanSquareRadius, pinhole.meanSquareRadius, expected);
  EXPECT_GT(circle, 10.0);
  EXPECT_NEAR(lens.meanSquareRadius, expected, 0.05 * expected);
  EXPECT_NEAR(lens.sum, pinhole.sum, 0.03 * pinhole.sum);  // the lens keeps the light (4 sigma of its noise)
}

TEST(DepthOfField, SphereAtTheFocusDistanceStaysSharp) {
  const Spread pinhole = spreadOf(lensScene(4.0, 0.0, 0.0));
  const Spread lens = spreadOf(lensScene(4.0, 0.5, 4.0));
  EXPECT_NEAR(lens.meanSquareRadius, pinhole.meanSquareRadius, 0.1 * pinhole.meanSquareRadius);
  EXPECT_NEAR(lens.sum, pinhole.sum, 0.02 * pinhole.sum);
}

TEST(DepthOfField, SameBytesForAnyThreadsAndTiles) {
  const Scene scene = lensScene(8.0, 0.5, 4.0);
  EXPECT_EQ(test::render(scene, 1, 64).image.rgb, test::render(scene, 2, 7).image.rgb);
}

TEST(DepthOfField, ApertureZeroIsThePinhole) {
  Scene scene = lensScene(8.0, 0.0, 0.0);
  scene.frame.camera.focusDistance = 3.0f;  // no lens: focus means nothing
  EXPECT_EQ(test::render(lensScene(8.0, 0.0, 0.0)).image.rgb, test::render(scene).image.rgb);
  EXPECT_FALSE(EffectPlan::derive(scene).depthOfField);
  EXPECT_TRUE(EffectPlan::derive(lensScene(8.0, 0.5, 4.0)).depthOfField);
}

}  // namespace
}  // namespace glint
