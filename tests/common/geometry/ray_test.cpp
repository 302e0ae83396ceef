// Ray's precomputed 1/d (common/geometry/ray.h): one four-lane division that must
// give, lane by lane, the bits of the scalar 1.0f / d, for every kind of
// component the tracer meets (signed zeros, subnormals, infinities).
#include "common/geometry/ray.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace glint {
namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

TEST(Ray, InverseDirectionIsTheScalarDivisionBitForBit) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<float> values{0.0f, -0.0f, 1.0f, -1.0f, std::numeric_limits<float>::denorm_min(),
                            -std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::min(),
                            std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                            1e-30f, 3.0f, 7.0f, 0.1f};
  for (int i = 0; i < 30000; ++i) values.push_back(unit(rng));
  for (std::size_t i = 0; i < values.size(); ++i) {
    const glm::vec3 d(values[i], values[(i * 7 + 1) % values.size()], values[(i * 13 + 2) % values.size()]);
    const Ray ray(glm::vec3(0.0f), d);
    for (int a = 0; a < 3; ++a) {
      ASSERT_TRUE(sameBits(ray.invD[a], 1.0f / d[a])) << "component " << a << " of direction " << i << ": " << d[a];
    }
  }
  EXPECT_EQ(Ray(glm::vec3(0.0f), {-0.0f, 0.0f, 1.0f}).invD.x, -std::numeric_limits<float>::infinity());
}

}  // namespace
}  // namespace glint
