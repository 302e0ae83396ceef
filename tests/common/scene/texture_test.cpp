#include "common/scene/texture.h"

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
