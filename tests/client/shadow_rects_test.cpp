#include "client/raster/shadow_rects.h"

#include <gtest/gtest.h>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>

namespace glint::gl {
namespace {

constexpr int kWidth = 200, kHeight = 150;
const glm::vec3 kEye(0.0f, 1.0f, 5.0f);

glm::mat4 viewProjection() {
  return glm::perspective(glm::radians(50.0f), float(kWidth) / kHeight, 0.1f, 100.0f) *
         glm::lookAt(kEye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
}

// A spot on the floor y = 0 (its light above), a square of side 2 * half.
ShadowSpot floorSpot(glm::vec3 centre, float half) {
  ShadowSpot s;
  for (int i = 0; i < 4; ++i) {
    s.corners[static_cast<std::size_t>(i)] =
        centre + glm::vec3(i & 1 ? half : -half, 0.0f, i & 2 ? half : -half);
  }
  s.cornerCount = 4;
  s.plane = {0.0f, 1.0f, 0.0f, 0.0f};
  return s;
}

// Each pixel's rectangle: -1 where none holds it, -2 where two do.
std::vector<int> cover(const std::vector<ScissorRect>& rects) {
  std::vector<int> owner(kWidth * kHeight, -1);
  for (int i = 0; i < static_cast<int>(rects.size()); ++i) {
    const ScissorRect& r = rects[static_cast<std::size_t>(i)];
    for (int y = r.y; y < r.y + r.height; ++y) {
      for (int x = r.x; x < r.x + r.width; ++x) {
        int& o = owner[static_cast<std::size_t>(y * kWidth + x)];
        o = o == -1 ? i : -2;
      }
    }
  }
  return owner;
}

TEST(ShadowRects, NoSpotNamesNothing) {
  const ShadowLayout layout = shadowLayout({}, viewProjection(), kEye, kWidth, kHeight);
  EXPECT_TRUE(layout.spotted.empty());
  EXPECT_TRUE(layout.rects.empty());
}

// A spot in view: the rectangles cover every pixel once, those under the
// spot's projected corners read the maps, and far from it they do not.
TEST(ShadowRects, SpotInViewIsCoveredExactlyOnce) {
  ShadowSpot spot = floorSpot({0.5f, 0.0f, 0.0f}, 0.3f);
  spot.prim = 7;
  ShadowSpot again = spot;  // a second light's spot on the same primitive
  again.light = 1;
  const ShadowLayout layout = shadowLayout({spot, again}, viewProjection(), kEye, kWidth, kHeight);
  EXPECT_EQ(layout.spotted, std::vector<std::uint32_t>{7});
  const std::vector<ScissorRect>& rects = layout.rects;
  EXPECT_GT(rects.size(), 2u);
  const std::vector<int> owner = cover(rects);
  for (int o : owner) ASSERT_GE(o, 0);
  const auto shadowsAt = [&](glm::vec3 p) {
    const WindowBox b = windowBox(std::span(&p, 1), viewProjection(), glm::vec2(kWidth, kHeight));
    const auto x = static_cast<int>(b.min.x), y = static_cast<int>(b.min.y);
    return rects[static_cast<std::size_t>(owner[static_cast<std::size_t>(y * kWidth + x)])].shadows;
  };
  for (int i = 0; i < 4; ++i)
    EXPECT_TRUE(shadowsAt(spot.corners[static_cast<std::size_t>(i)])) << i;
  EXPECT_TRUE(shadowsAt({0.5f, 0.0f, 0.0f}));
  EXPECT_FALSE(shadowsAt({-2.0f, 0.0f, 1.0f}));
}

// Seen from below its plane (the side away from its light) a spot does not
// count; reaching behind the eye, it covers the frame.
TEST(ShadowRects, SpotSeenFromBehindOrReachingBehindTheEye) {
  ShadowSpot below = floorSpot({0.5f, 2.0f, 0.0f}, 0.3f);
  below.plane = {0.0f, 1.0f, 0.0f, 2.0f};  // y = 2, light above: the eye at y = 1 is below
  EXPECT_TRUE(shadowLayout({below}, viewProjection(), kEye, kWidth, kHeight).spotted.empty());
  const ShadowLayout behind =
      shadowLayout({floorSpot({0.0f, 0.0f, 5.0f}, 2.0f)}, viewProjection(), kEye, kWidth, kHeight);
  ASSERT_EQ(behind.rects.size(), 1u);
  EXPECT_TRUE(behind.rects[0].shadows);
  EXPECT_EQ(behind.rects[0].width, kWidth);
  EXPECT_EQ(behind.rects[0].height, kHeight);
}

}  // namespace
}  // namespace glint::gl
