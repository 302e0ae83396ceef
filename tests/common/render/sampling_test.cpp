#include "common/render/sampling.h"

#include <set>

#include <gtest/gtest.h>

namespace glint {
namespace {

SamplingSettings settings(SamplePattern p, int n, std::uint32_t seed = 0) {
  SamplingSettings s;
  s.pattern = p;
  s.samples = n;
  s.seed = seed;
  return s;
}

TEST(Sampling, RegularGridsAreCellCentres) {
  EXPECT_EQ(SampleLayout(settings(SamplePattern::kRegular, 1)).position(3, 4, 0), glm::vec2(0.5f));
  EXPECT_EQ(SampleLayout(settings(SamplePattern::kRegular, 2)).position(3, 4, 0), glm::vec2(0.25f));
  EXPECT_EQ(SampleLayout(settings(SamplePattern::kRegular, 2)).position(3, 4, 1), glm::vec2(0.75f));
  const auto s4 = settings(SamplePattern::kRegular, 4);
  EXPECT_EQ(SampleLayout(s4).position(0, 0, 0), glm::vec2(0.25f, 0.25f));
  EXPECT_EQ(SampleLayout(s4).position(0, 0, 1), glm::vec2(0.75f, 0.25f));
  EXPECT_EQ(SampleLayout(s4).position(0, 0, 2), glm::vec2(0.25f, 0.75f));
  EXPECT_EQ(SampleLayout(s4).position(0, 0, 3), glm::vec2(0.75f, 0.75f));
}

// Every jittered sample lies in [0, 1) and in its own stratum; the strata
// have equal area and cover the pixel.
TEST(Sampling, JitteredSamplesStayInTheirStrata) {
  for (int n : {1, 2, 3, 4, 5, 7, 8, 16, 33, 100}) {
    float area = 0.0f;
    for (int i = 0; i < n; ++i) {
      const Stratum st = jitteredStratum(n, i);
      EXPECT_NEAR((st.x1 - st.x0) * (st.y1 - st.y0), 1.0f / n, 1e-6f) << n << " " << i;
      area += (st.x1 - st.x0) * (st.y1 - st.y0);
    }
    EXPECT_NEAR(area, 1.0f, 1e-5f);
    const auto s = settings(SamplePattern::kJittered, n, 42);
    for (int px = 0; px < 40; ++px) {
      for (int i = 0; i < n; ++i) {
        const glm::vec2 p = SampleLayout(s).position(px, 7, i);
        const Stratum st = jitteredStratum(n, i);
        ASSERT_GE(p.x, st.x0);
        ASSERT_LT(p.x, st.x1);
        ASSERT_GE(p.y, st.y0);
        ASSERT_LT(p.y, st.y1);
        ASSERT_LT(p.x, 1.0f);
        ASSERT_LT(p.y, 1.0f);
      }
    }
  }
}

// One sample per stratum: each sample is found in exactly one stratum.
TEST(Sampling, EachStratumGetsExactlyOneSample) {
  for (int n : {3, 5, 16, 33}) {
    const auto s = settings(SamplePattern::kJittered, n, 1);
    std::vector<int> count(static_cast<std::size_t>(n), 0);
    for (int i = 0; i < n; ++i) {
      const glm::vec2 p = SampleLayout(s).position(5, 5, i);
      for (int k = 0; k < n; ++k) {
        const Stratum st = jitteredStratum(n, k);
        if (p.x >= st.x0 && p.x < st.x1 && p.y >= st.y0 && p.y < st.y1) ++count[static_cast<std::size_t>(k)];
      }
    }
    for (int c : count) EXPECT_EQ(c, 1) << n;
  }
}

// A jittered sample lies at hashUniform's dimensions 0 and 1 across its
// stratum (hashed once per sample for both, the same values).
TEST(Sampling, JitteredSamplesAreTheHashAcrossTheStratum) {
  for (int n : {1, 4, 7}) {
    const auto s = settings(SamplePattern::kJittered, n, 5);
    const SampleLayout layout(s);
    for (int px = 0; px < 30; ++px) {
      for (int i = 0; i < n; ++i) {
        const Stratum st = jitteredStratum(n, i);
        const glm::vec2 p = layout.position(px, 11, i);
        ASSERT_EQ(p.x, st.x0 + hashUniform(5, px, 11, i, 0) * (st.x1 - st.x0)) << n << " " << px << " " << i;
        ASSERT_EQ(p.y, st.y0 + hashUniform(5, px, 11, i, 1) * (st.y1 - st.y0)) << n << " " << px << " " << i;
      }
    }
  }
}

TEST(Sampling, HashIsAPureFunctionOfSeedPixelAndSample) {
  const auto a = settings(SamplePattern::kJittered, 4, 9);
  // Visiting pixels forwards and backwards gives the same values.
  std::vector<glm::vec2> forward, backward;
  for (int x = 0; x < 50; ++x) forward.push_back(SampleLayout(a).position(x, 3, 2));
  for (int x = 49; x >= 0; --x) backward.insert(backward.begin(), SampleLayout(a).position(x, 3, 2));
  EXPECT_EQ(forward, backward);
  // Another seed moves (nearly) every sample.
  const auto b = settings(SamplePattern::kJittered, 4, 10);
  int same = 0;
  for (int x = 0; x < 50; ++x) same += SampleLayout(b).position(x, 3, 2) == forward[static_cast<std::size_t>(x)] ? 1 : 0;
  EXPECT_LT(same, 2);
  // Values are in [0, 1) and look uniform.
  double sum = 0.0;
  for (int i = 0; i < 100'000; ++i) {
    const float u = hashUniform(1, i, 2, 3, 0);
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    sum += u;
  }
  EXPECT_NEAR(sum / 100'000, 0.5, 0.005);
}

}  // namespace
}  // namespace glint
