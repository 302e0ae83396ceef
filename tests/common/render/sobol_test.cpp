// The scrambled Sobol points a path draws its choices from: for any seed,
// the first 2^k points are a (0,2)-net (one point in each of the 2^k cells
// of every shape 2^-a x 2^-b, a + b = k), and seeds scramble apart.
#include "common/render/sobol.h"

#include <set>
#include <vector>

#include <gtest/gtest.h>

namespace glint {
namespace {

// Whether the first 2^k points of `seed` put one in each elementary cell.
bool isNet(int k, std::uint32_t seed) {
  const std::uint32_t n = 1u << k;
  std::vector<glm::vec2> points;
  for (std::uint32_t i = 0; i < n; ++i) points.push_back(scrambledSobol(i, seed));
  for (int a = 0; a <= k; ++a) {
    const std::uint32_t columns = 1u << a, rows = 1u << (k - a);
    std::vector<int> count(n, 0);
    for (const glm::vec2& p : points) {
      if (!(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f)) return false;
      const auto cx = static_cast<std::uint32_t>(p.x * static_cast<float>(columns));
      const auto cy = static_cast<std::uint32_t>(p.y * static_cast<float>(rows));
      if (++count[cy * columns + cx] > 1) return false;
    }
  }
  return true;
}

TEST(ScrambledSobol, EveryPowerOfTwoPrefixIsANet) {
  for (const std::uint32_t seed : {0u, 1u, 0xdeadbeefu, 0x12345678u, 0xffffffffu}) {
    for (int k = 0; k <= 12; ++k) EXPECT_TRUE(isNet(k, seed)) << "seed " << seed << ", 2^" << k << " points";
  }
}

TEST(ScrambledSobol, SeedsScrambleApart) {
  std::set<std::pair<float, float>> firsts;
  for (std::uint32_t seed = 0; seed < 64; ++seed) {
    const glm::vec2 p = scrambledSobol(0, seed);
    firsts.insert({p.x, p.y});
  }
  EXPECT_EQ(firsts.size(), 64u);  // the first point, too, moves with the seed
  // Two seeds' points are not the same points in another order.
  std::set<std::pair<float, float>> a, b;
  for (std::uint32_t i = 0; i < 16; ++i) {
    const glm::vec2 p = scrambledSobol(i, 7), q = scrambledSobol(i, 8);
    a.insert({p.x, p.y});
    b.insert({q.x, q.y});
  }
  EXPECT_NE(a, b);
}

}  // namespace
}  // namespace glint
