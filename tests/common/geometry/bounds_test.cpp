#include "common/geometry/bounds.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(Bounds, DefaultIsEmptyAndUnionNeedsNoSpecialCase) {
  Bounds3 b;
  EXPECT_TRUE(b.empty());
  EXPECT_EQ(b.surfaceArea(), 0.0f);
  b.expand(glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_FALSE(b.empty());
  EXPECT_EQ(b.min, glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(b.max, glm::vec3(1.0f, 2.0f, 3.0f));
  b.expand(Bounds3{{0.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 2.0f}});
  EXPECT_EQ(b.max, glm::vec3(2.0f, 2.0f, 3.0f));
  EXPECT_FLOAT_EQ(b.surfaceArea(), 2.0f * (2 * 2 + 2 * 3 + 3 * 2));
}

// A point is inside on the boundary too; an empty box holds nothing.
TEST(Bounds, ContainsItsInsideAndBoundary) {
  const Bounds3 b{glm::vec3(-1.0f, 0.0f, 2.0f), glm::vec3(1.0f, 3.0f, 4.0f)};
  EXPECT_TRUE(b.contains(glm::vec3(0.0f, 1.0f, 3.0f)));
  EXPECT_TRUE(b.contains(glm::vec3(1.0f, 3.0f, 2.0f)));
  EXPECT_FALSE(b.contains(glm::vec3(1.0001f, 1.0f, 3.0f)));
  EXPECT_FALSE(b.contains(glm::vec3(0.0f, -0.5f, 3.0f)));
  EXPECT_FALSE(Bounds3{}.contains(glm::vec3(0.0f)));
}

// The eight corners, each once, bit i of the index choosing max on axis i.
TEST(Bounds, CornersAreTheEightCombinations) {
  const Bounds3 b{glm::vec3(-1.0f, 0.0f, 2.0f), glm::vec3(1.0f, 3.0f, 4.0f)};
  const auto c = b.corners();
  EXPECT_EQ(c[0], b.min);
  EXPECT_EQ(c[7], b.max);
  EXPECT_EQ(c[1], glm::vec3(1.0f, 0.0f, 2.0f));
  EXPECT_EQ(c[2], glm::vec3(-1.0f, 3.0f, 2.0f));
  EXPECT_EQ(c[4], glm::vec3(-1.0f, 0.0f, 4.0f));
  for (std::size_t i = 0; i < 8; ++i) {
    for (std::size_t j = i + 1; j < 8; ++j) EXPECT_NE(c[i], c[j]);
  }
}

}  // namespace
}  // namespace glint
