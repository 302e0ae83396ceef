// Output encoding: the sRGB transfer function against the standard's values,
// the default encoding leaves every 8-bit value as it was, exposure scales by
// powers of two, and a frame's tiles are its linear values encoded.
#include "common/image/encoding.h"

#include <gtest/gtest.h>

#include "common/render/frame.h"
#include "common/render/linear_frame.h"
#include "common/render/prepared_scene.h"
#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

// x^(1/2.4) is power()'s nearest float: glibc's powf (either version)
// rounds this one an ulp up (0x1.72aa7p-4).
TEST(Encoding, SrgbTakesTheNearestPower) {
  volatile float x = 0x1.9a95f6p-9f;  // volatile: not worked out by the compiler
  EXPECT_EQ(srgbEncode(x), 1.055f * 0x1.72aa6ep-4f - 0.055f);
}

TEST(Encoding, SrgbTransferFunctionMatchesTheStandard) {
  // IEC 61966-2-1: 12.92 x up to 0.0031308, 1.055 x^(1/2.4) - 0.055 above.
  EXPECT_EQ(srgbEncode(0.0f), 0.0f);
  EXPECT_NEAR(srgbEncode(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(srgbEncode(0.0031308f), 0.0404500f, 1e-5f);  // the two pieces meet
  EXPECT_NEAR(srgbEncode(0.001f), 0.01292f, 1e-7f);
  EXPECT_NEAR(srgbEncode(0.18f), 0.4613561f, 1e-5f);  // middle grey
  EXPECT_NEAR(srgbEncode(0.5f), 0.7353570f, 1e-5f);
  const Encoder srgb({Encoding::kSrgb, 0.0f});
  EXPECT_EQ(srgb.byte(0.5f), 188);
  EXPECT_EQ(srgb.byte(0.18f), 118);
}

// The default is sRGB, as a display shows a PNG (below); linear, the
// thesis's frame buffer, stores each value as it is.
TEST(Encoding, LinearLeavesEveryByteAsItWas) {
  EXPECT_EQ(OutputSettings{}.encoding, Encoding::kSrgb);
  const Encoder linear({Encoding::kLinear, 0.0f});
  for (int b = 0; b < 256; ++b) {
    const float v = static_cast<float>(b) / 255.0f;
    EXPECT_EQ(linear.byte(v), toByte(v)) << b;
    EXPECT_EQ(linear.byte(v), b);
  }
  EXPECT_EQ(linear.byte(2.0f), 255);
  EXPECT_EQ(linear.byte(-1.0f), 0);
}

TEST(Encoding, ExposureScalesByPowersOfTwo) {
  EXPECT_EQ(Encoder({Encoding::kLinear, 1.0f}).byte(0.25f), 128);   // 0.5 * 255 = 127.5
  EXPECT_EQ(Encoder({Encoding::kLinear, -1.0f}).byte(1.0f), 128);
  EXPECT_EQ(Encoder({Encoding::kLinear, 2.0f}).byte(0.5f), 255);    // clamped after scaling
  EXPECT_EQ(Encoder({Encoding::kLinear, -2.0f}).scaled(glm::vec3(4.0f)), glm::vec3(1.0f));
}

// The tiles' bytes are the frame's linear values, scaled and encoded: the
// same pixels as the linear image through the encoder.
TEST(Encoding, TilesAreTheLinearFrameEncoded) {
  const Scene scene = loadSceneFile(test::sourcePath("scenes/room.json"));
  const PreparedScene prepared(scene, BvhSettings{});
  FrameSettings frame = scene.frame;
  frame.width = 48;
  frame.height = 36;
  frame.output = {Encoding::kSrgb, 0.5f};
  ThreadPool pool(2);
  const Renderer renderer(prepared, frame);
  const FrameImage bytes = renderFrame(renderer, pool, {}).image;
  RayStats stats;
  const LinearImage linear = renderLinear(renderer, pool, stats, LinearRange::kUnbounded);
  const Encoder encoder(frame.output);
  ASSERT_EQ(bytes.rgb.size(), linear.rgb.size());
  int brighter = 0;
  for (std::size_t i = 0; i < bytes.rgb.size(); ++i) {
    ASSERT_EQ(bytes.rgb[i], encoder.byte(linear.rgb[i])) << i;
    brighter += bytes.rgb[i] > toByte(linear.rgb[i]) ? 1 : 0;
  }
  EXPECT_GT(brighter, static_cast<int>(bytes.rgb.size()) / 2);  // sRGB and +0.5 EV lift the frame
}

}  // namespace
}  // namespace glint
