#include "common/bounds.h"

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

}  // namespace
}  // namespace glint
