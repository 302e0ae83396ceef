#include "common/render/filter.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/render/sampling.h"

namespace glint {
namespace {

TEST(Filter, CentreMapsToCentreAndWarpIsMonotonic) {
  for (FilterType type : {FilterType::kBox, FilterType::kTent, FilterType::kGaussian, FilterType::kMitchell}) {
    const Filter f(type);
    EXPECT_EQ(f.warp(0.5f), 0.0f);
    float last = -1e9f;
    for (int i = 0; i < 1000; ++i) {
      const float x = f.warp((static_cast<float>(i) + 0.5f) / 1000.0f);
      EXPECT_GE(x, last);
      EXPECT_GE(x, -f.radius());
      EXPECT_LE(x, f.radius());
      last = x;
    }
  }
}

// The tent filter's warped samples follow the tent distribution: a
// chi-square test over 20 bins (critical value 43.8 at p = 0.001, 19 dof).
TEST(Filter, TentSamplesFollowTheTentDistribution) {
  const Filter tent(FilterType::kTent);
  constexpr int kBins = 20;
  constexpr int kSamples = 200'000;
  std::vector<int> counts(kBins, 0);
  for (int i = 0; i < kSamples; ++i) {
    const float x = tent.warp(hashUniform(3, i, 0, 0, 0));
    const int bin = std::min(kBins - 1, static_cast<int>((x + 1.0f) * 0.5f * kBins));
    ++counts[static_cast<std::size_t>(bin)];
  }
  const auto cdf = [](double x) { return x < 0 ? 0.5 * (1 + x) * (1 + x) : 1 - 0.5 * (1 - x) * (1 - x); };
  double chi2 = 0.0;
  for (int b = 0; b < kBins; ++b) {
    const double lo = -1.0 + 2.0 * b / kBins, hi = -1.0 + 2.0 * (b + 1) / kBins;
    const double expected = kSamples * (cdf(hi) - cdf(lo));
    chi2 += (counts[static_cast<std::size_t>(b)] - expected) * (counts[static_cast<std::size_t>(b)] - expected) / expected;
  }
  EXPECT_LT(chi2, 43.8);
}

TEST(Filter, MitchellHasNegativeLobes) {
  const Filter m(FilterType::kMitchell);
  EXPECT_GT(m.evaluate(0.0f), 0.0f);
  EXPECT_LT(m.evaluate(1.5f), 0.0f);
  EXPECT_EQ(m.sign(1.5f), -1.0f);
  EXPECT_EQ(m.sign(0.2f), 1.0f);
}

}  // namespace
}  // namespace glint
