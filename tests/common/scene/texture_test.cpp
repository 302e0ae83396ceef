#include "common/scene/texture.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "common/scene/gltf_texture_transform.h"

namespace glint {
namespace {

TEST(Texture, CheckerIndexFollowsTheFormat) {
  // (floor(u s) + floor(v s)) mod 2.
  EXPECT_EQ(checkerIndex({0.1f, 0.1f}, 1.0f), 0);
  EXPECT_EQ(checkerIndex({1.1f, 0.1f}, 1.0f), 1);
  EXPECT_EQ(checkerIndex({0.1f, 1.1f}, 1.0f), 1);
  EXPECT_EQ(checkerIndex({1.1f, 1.1f}, 1.0f), 0);
  EXPECT_EQ(checkerIndex({-0.1f, 0.1f}, 1.0f), 1);  // floor(-0.1) = -1
  EXPECT_EQ(checkerIndex({0.3f, 0.1f}, 4.0f), 1);   // floor(1.2) = 1
  EXPECT_EQ(checkerIndex({1e30f, 0.0f}, 1e10f), 0);  // overflow: not finite, first colour
}

// The parity of sums of every size, against fmod's: odd products of two
// odd floats up to 2^48, sums near and past 2^53 (where every double is even).
TEST(Texture, CheckerIndexIsTheParityAtEveryMagnitude) {
  const auto byFmod = [](const glm::vec2& uv, float scale) {
    const double sum = std::floor(double(uv.x) * scale) + std::floor(double(uv.y) * scale);
    return std::fmod(std::abs(sum), 2.0) == 1.0 ? 1 : 0;
  };
  int odd = 0;
  for (float a : {1.0f, 3.0f, 16777215.0f, -16777215.0f, 0x1p52f, 0x1p53f, 0x1p60f, 3.5f, -2.5f}) {
    for (float b : {1.0f, 16777213.0f, 1.25f}) {
      for (float v : {0.0f, 1.0f, 0x1p52f, -0x1p52f + 1.0f}) {
        const glm::vec2 uv{a, v};
        EXPECT_EQ(checkerIndex(uv, b), byFmod(uv, b)) << a << " " << b << " " << v;
        odd += byFmod(uv, b);
      }
    }
  }
  EXPECT_GT(odd, 10);  // the cases include odd sums, large ones among them
  EXPECT_EQ(checkerIndex({16777215.0f, 0.0f}, 16777213.0f), 1);  // 281474943156195, odd
}

TEST(Texture, ImageUvRunsRightAndUp) {
  auto image = std::make_shared<Image>();
  image->width = 2;
  image->height = 2;
  // Row 0 is the top of the image.
  image->rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
  Texture t;
  t.type = TextureType::kImage;
  t.image = image;
  EXPECT_EQ(t.evaluate({0.25f, 0.75f}), glm::vec3(1, 0, 0));  // top-left
  EXPECT_EQ(t.evaluate({0.75f, 0.75f}), glm::vec3(0, 1, 0));  // top-right
  EXPECT_EQ(t.evaluate({0.25f, 0.25f}), glm::vec3(0, 0, 1));  // bottom-left
  EXPECT_EQ(t.evaluate({1.25f, -0.75f}), glm::vec3(0, 0, 1));  // wraps
  t.filter = ImageFilter::kBilinear;
  EXPECT_EQ(t.evaluate({0.25f, 0.75f}), glm::vec3(1, 0, 0));  // a texel centre is exact
  const glm::vec3 mid = t.evaluate({0.5f, 0.75f});            // halfway between the top texels
  EXPECT_NEAR(mid.x, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.y, 0.5f, 1e-6f);
}

// A 4 x 1 image whose texels are 0, 1, 2, 3 (x 10 / 255), read nearest
// along u: the texel index each wrap mode reads, worked out from OpenGL's
// definition (its specification's mirror(), clamp to the edge texel
// centres' range) for coordinates across three periods.
TEST(Texture, WrapModesReadAsOpenGLDefinesThem) {
  auto image = std::make_shared<Image>();
  image->width = 4;
  image->height = 1;
  for (int i = 0; i < 4; ++i) image->rgb.insert(image->rgb.end(), 3, static_cast<std::uint8_t>(10 * i));
  Texture t;
  t.type = TextureType::kImage;
  t.image = image;
  const auto index = [&](float u) { return static_cast<int>(std::lround(t.evaluate({u, 0.5f}).x * 255.0f / 10.0f)); };
  const auto byDefinition = [](TextureWrap mode, double u) {
    const double s = u * 4.0;  // texel space
    const int i = static_cast<int>(std::floor(s));
    switch (mode) {
      case TextureWrap::kRepeat:
        return ((i % 4) + 4) % 4;
      case TextureWrap::kMirroredRepeat: {
        // mirror(a) = a for a >= 0, -(1 + a) otherwise, on (i mod 8) - 4.
        const int a = ((i % 8) + 8) % 8 - 4;
        return 3 - (a >= 0 ? a : -(1 + a));
      }
      case TextureWrap::kClampToEdge:
        return std::clamp(i, 0, 3);
    }
    return -1;
  };
  for (const TextureWrap mode : {TextureWrap::kRepeat, TextureWrap::kMirroredRepeat, TextureWrap::kClampToEdge}) {
    t.wrap = {mode, TextureWrap::kRepeat};
    for (float u = -3.0f + 0.0625f; u < 3.0f; u += 0.125f) {
      EXPECT_EQ(index(u), byDefinition(mode, u)) << enumWord(mode) << " at u = " << u;
    }
  }
  // Mirrored: the copy right of the image runs backwards, the next forwards.
  t.wrap = {TextureWrap::kMirroredRepeat, TextureWrap::kRepeat};
  EXPECT_EQ(index(1.125f), 3);
  EXPECT_EQ(index(1.875f), 0);
  EXPECT_EQ(index(2.125f), 0);
  // Bilinear at the edge: repeat blends in the far edge's texel, clamp the
  // edge texel itself, mirror the edge texel (its own mirror image).
  t.filter = ImageFilter::kBilinear;
  t.wrap = {TextureWrap::kRepeat, TextureWrap::kRepeat};
  EXPECT_NEAR(t.evaluate({1.0f, 0.5f}).x * 255.0f, 15.0f, 1e-3f);  // halfway between texels 3 and 0
  t.wrap = {TextureWrap::kClampToEdge, TextureWrap::kRepeat};
  EXPECT_NEAR(t.evaluate({1.0f, 0.5f}).x * 255.0f, 30.0f, 1e-3f);
  t.wrap = {TextureWrap::kMirroredRepeat, TextureWrap::kRepeat};
  EXPECT_NEAR(t.evaluate({1.0f, 0.5f}).x * 255.0f, 30.0f, 1e-3f);
}

// v wraps by its own mode, with v up (row 0 at the top).
TEST(Texture, WrapAlongVIsItsOwn) {
  auto image = std::make_shared<Image>();
  image->width = 1;
  image->height = 2;
  image->rgb = {255, 255, 255, 0, 0, 0};  // top white, bottom black
  Texture t;
  t.type = TextureType::kImage;
  t.image = image;
  t.wrap = {TextureWrap::kMirroredRepeat, TextureWrap::kClampToEdge};
  EXPECT_EQ(t.evaluate({0.5f, 1.75f}).x, 1.0f);   // clamped to the top row
  EXPECT_EQ(t.evaluate({0.5f, -0.75f}).x, 0.0f);  // clamped to the bottom row
  t.wrap = {TextureWrap::kClampToEdge, TextureWrap::kMirroredRepeat};
  EXPECT_EQ(t.evaluate({0.5f, 1.25f}).x, 1.0f);   // mirrored: above the top comes the top again
  EXPECT_EQ(t.evaluate({0.5f, 1.75f}).x, 0.0f);
  t.wrap = {TextureWrap::kClampToEdge, TextureWrap::kRepeat};
  EXPECT_EQ(t.evaluate({0.5f, 1.25f}).x, 0.0f);   // repeated: above the top comes the bottom
}

// The extension's own example: offset (0, 1), rotation 90 degrees, scale
// 0.5 "utilizes only the lower left quadrant of the source image, rotated
// clockwise 90 degrees". In Glint's uv (v up) the quadrant is [0, 0.5]^2,
// and turned clockwise the quad's top left (0, 1) shows the quadrant's
// bottom left (0, 0), its top right (1, 1) the quadrant's top left (0, 0.5),
// its bottom left (0, 0) the quadrant's bottom right (0.5, 0).
TEST(Texture, KhrTextureTransformAsTheExtensionsExample) {
  const UvTransform t = glintUvTransform({{0.0, 1.0}, M_PI / 2.0, {0.5, 0.5}});
  const std::pair<glm::vec2, glm::vec2> corners[] = {
      {{0, 1}, {0, 0}}, {{1, 1}, {0, 0.5}}, {{0, 0}, {0.5, 0}}, {{1, 0}, {0.5, 0.5}}};
  for (const auto& [quad, image] : corners) {
    const glm::vec2 got = t.apply(quad);
    EXPECT_NEAR(got.x, image.x, 1e-6) << quad.x << "," << quad.y;
    EXPECT_NEAR(got.y, image.y, 1e-6) << quad.x << "," << quad.y;
  }
  // No transform is the identity, bit for bit.
  const UvTransform identity = glintUvTransform({});
  for (const glm::vec2 uv : {glm::vec2(0.3f, 0.7f), glm::vec2(-12.25f, 3e5f), glm::vec2(1e-30f, 1.0f)}) {
    EXPECT_EQ(identity.apply(uv), uv);
  }
}

}  // namespace
}  // namespace glint
