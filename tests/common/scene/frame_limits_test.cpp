// One check of a frame's settings, named by each caller its own way.
#include "common/scene/frame_limits.h"

#include <gtest/gtest.h>

#include <limits>

#include "common/base/error.h"

namespace glint {
namespace {

FrameSettings goodFrame() {
  FrameSettings f;
  f.camera.eye = {0, 0, 5};
  return f;
}

TEST(FrameLimits, EachSettingOutOfRangeIsNamed) {
  EXPECT_FALSE(frameProblem(goodFrame()));
  const struct {
    void (*edit)(FrameSettings&);
    FrameField field;
  } cases[] = {
      {[](FrameSettings& f) { f.width = 0; }, FrameField::kSize},
      {[](FrameSettings& f) { f.height = FrameLimits::kMaxEdge + 1; }, FrameField::kSize},
      {[](FrameSettings& f) { f.width = f.height = 20000; }, FrameField::kSize},  // over kMaxPixels
      {[](FrameSettings& f) { f.camera.lookAt = f.camera.eye; }, FrameField::kCamera},
      {[](FrameSettings& f) { f.sampling.samples = FrameLimits::kMaxSamples + 1; }, FrameField::kSamples},
      {[](FrameSettings& f) { f.sampling.samples = 3; }, FrameField::kSamples},  // regular: 1, 2 or a square
      {[](FrameSettings& f) { f.sampling.seed = FrameLimits::kMaxSeed + 1; }, FrameField::kSeed},
      {[](FrameSettings& f) { f.tracing.maxDepth = 0; }, FrameField::kMaxDepth},
      {[](FrameSettings& f) { f.tracing.minWeight = -0.5f; }, FrameField::kMinWeight},
  };
  for (const auto& c : cases) {
    FrameSettings f = goodFrame();
    c.edit(f);
    const auto problem = frameProblem(f);
    ASSERT_TRUE(problem);
    EXPECT_EQ(problem->field, c.field) << problem->what;
  }
  FrameSettings jittered = goodFrame();
  jittered.sampling.pattern = SamplePattern::kJittered;
  jittered.sampling.samples = 3;
  EXPECT_FALSE(frameProblem(jittered));
}

TEST(FrameLimits, TheRegularPatternTakesSquaresAndTwo) {
  for (int n : {1, 2, 4, 9, 16, 64}) EXPECT_TRUE(validSampleCount(SamplePattern::kRegular, n)) << n;
  for (int n : {0, 3, 5, 8, 15, 17, 63}) EXPECT_FALSE(validSampleCount(SamplePattern::kRegular, n)) << n;
  for (int n : {1, 3, 5, 63}) EXPECT_TRUE(validSampleCount(SamplePattern::kJittered, n)) << n;
  EXPECT_FALSE(validSampleCount(SamplePattern::kAdaptive, 0));
}

TEST(FrameLimits, CheckFrameUsesTheCallersNames) {
  const FrameFieldNames names{.size = "--size",
                              .camera = "camera.",
                              .samples = "--samples",
                              .seed = "--seed",
                              .maxDepth = "--max-depth",
                              .maxBounces = "--max-bounces",
                              .minWeight = "--min-weight",
                              .adaptiveThreshold = "--adaptive-threshold",
                              .perceptualThreshold = "--perceptual-threshold",
                              .lightSamples = "--light-samples",
                              .exposure = "--exposure"};
  FrameSettings f = goodFrame();
  f.tracing.maxDepth = 65;
  try {
    checkFrame(f, FrameLimits::kMaxPixels, names);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--max-depth: must be in [1, 64]");
  }
  f = goodFrame();
  f.camera.up = {0, 0, 0};
  try {
    checkFrame(f, FrameLimits::kMaxPixels, names);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "camera.up: must not be the zero vector");
  }
  f = goodFrame();
  f.output.exposure = std::numeric_limits<float>::infinity();
  try {
    checkFrame(f, FrameLimits::kMaxPixels, names);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--exposure: must be in [-32, 32] (EV)");
  }
  f = goodFrame();
  f.sampling.perceptualThreshold = 0.0f;
  try {
    checkFrame(f, FrameLimits::kMaxPixels, names);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--perceptual-threshold: must be in (0, 1]");
  }
  f = goodFrame();
  f.sampling.lightSamples = FrameLimits::kMaxLightSamples + 1;
  try {
    checkFrame(f, FrameLimits::kMaxPixels, names);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--light-samples: must be in [0, 4096] (0: each light's own)");
  }
}

}  // namespace
}  // namespace glint
