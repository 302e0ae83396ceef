// Glossy reflection: the lobe's microfacet normals against the GGX
// distribution integrated here in double precision; a rough floor keeps the
// light it reflects, blurs a reflected edge more the rougher it is, and at
// roughness 0 is the mirror; the same bytes however the frame is split.
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/render/glossy_lobe.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;

// P(theta_h < theta) of the GGX normal distribution weighted by cos theta_h:
// the integral of D(h) cos theta_h over the cap, D = alpha^2 /
// (pi cos^4 theta (alpha^2 + tan^2 theta)^2), by Simpson's rule.
double ggxCapShare(double alpha, double theta) {
  constexpr int kSteps = 4000;
  const auto f = [alpha](double t) {
    const double c = std::cos(t), tan2 = std::tan(t) * std::tan(t);
    const double d = alpha * alpha / (kPi * c * c * c * c * (alpha * alpha + tan2) * (alpha * alpha + tan2));
    return d * c * 2.0 * kPi * std::sin(t);
  };
  const double h = theta / kSteps;
  double sum = f(0.0) + f(theta);
  for (int i = 1; i < kSteps; ++i) sum += f(i * h) * (i % 2 ? 4.0 : 2.0);
  return sum * h / 3.0;
}

TEST(GlossyLobe, MicrofacetNormalsFollowTheGgxDistribution) {
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f));
  constexpr int kGrid = 400;  // a 400 x 400 grid of u: the distribution, not noise
  for (const float alpha : {0.05f, 0.3f, 0.8f}) {
    const double angles[] = {0.5 * alpha, alpha, 2.0 * alpha, 0.9 * kPi / 2.0};
    int below[4] = {0, 0, 0, 0};
    double sinPhiSum = 0.0;
    for (int i = 0; i < kGrid; ++i) {
      for (int j = 0; j < kGrid; ++j) {
        const glm::vec3 h = ggxMicrofacetNormal(n, alpha, {(i + 0.5f) / kGrid, (j + 0.5f) / kGrid});
        ASSERT_NEAR(glm::length(h), 1.0f, 1e-5f);
        const double theta = std::acos(std::clamp(static_cast<double>(glm::dot(h, n)), -1.0, 1.0));
        for (int k = 0; k < 4; ++k) below[k] += theta < angles[k] ? 1 : 0;
        sinPhiSum += glm::dot(glm::cross(n, h), glm::vec3(1, 0, 0));
      }
    }
    for (int k = 0; k < 4; ++k) {
      const double share = static_cast<double>(below[k]) / (kGrid * kGrid);
      EXPECT_NEAR(share, ggxCapShare(alpha, angles[k]), 3e-3) << "alpha " << alpha << " theta " << angles[k];
    }
    EXPECT_NEAR(sinPhiSum / (kGrid * kGrid), 0.0, 1e-3) << "azimuth not uniform at alpha " << alpha;
  }
}

TEST(GlossyLobe, EveryDirectionLeavesAboveTheSurface) {
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  const glm::vec3 grazing = glm::normalize(glm::vec3(1.0f, -0.05f, 0.0f));
  for (int i = 0; i < 64; ++i) {
    for (int j = 0; j < 64; ++j) {
      const glm::vec3 r = glossyDirection(grazing, n, n, 1.0f, {(i + 0.5f) / 64, (j + 0.5f) / 64});
      EXPECT_GT(glm::dot(r, n), 0.0f);
      EXPECT_NEAR(glm::length(r), 1.0f, 1e-5f);
    }
  }
}

// A reflecting floor (no light of its own) seen from above, reflecting a
// bright emitting wall whose right edge stands at x = 0, on black.
json wallScene(std::optional<float> roughness, int samples) {
  json mirror = {{"diffuse", 0}, {"reflectivity", 1}};
  if (roughness) mirror["roughness"] = *roughness;
  return {{"glint", 1},
          {"image", {{"width", 96}, {"height", 64}}},
          {"camera", {{"eye", {0, 1.5, 4}}, {"look_at", {0, 0, 0}}, {"fov_y", 45}}},
          {"sampling", {{"pattern", "jittered"}, {"samples", samples}}},
          {"background", {0, 0, 0}},
          {"materials",
           {{"mirror", mirror}, {"wall", {{"diffuse", 0}, {"emission", {1, 1, 1}}}}}},
          {"objects",
           {{{"type", "quad"}, {"corners", {{-6, 0, 3}, {6, 0, 3}, {6, 0, -6}, {-6, 0, -6}}}, {"material", "mirror"}},
            {{"type", "quad"}, {"corners", {{-6, 0, -3}, {0, 0, -3}, {0, 3, -3}, {-6, 3, -3}}}, {"material", "wall"}}}}};
}

// Columns a row takes to go from 90 % to 10 % of the wall's reflection.
int edgeWidth(const FrameImage& image, int y) {
  int width = 0;
  for (int x = 0; x < image.width; ++x) {
    const int g = test::pixelAt(image, x, y).g;
    width += g > 25 && g < 230 ? 1 : 0;
  }
  return width;
}

constexpr int kFloorRow = 36;  // a row of the floor, the wall's reflection across its left half

TEST(GlossyReflection, ReflectedEdgeBlursMoreTheRougherTheFloor) {
  const FrameImage mirror = test::render(test::sceneFromJson(wallScene(std::nullopt, 64).dump()), 2).image;
  ASSERT_GT(test::pixelAt(mirror, 10, kFloorRow).g, 240) << "the row must show the wall's reflection";
  ASSERT_LT(test::pixelAt(mirror, 85, kFloorRow).g, 10);
  int previous = edgeWidth(mirror, kFloorRow);
  EXPECT_LE(previous, 2) << "the mirror's reflected edge is sharp";
  for (const float r : {0.15f, 0.3f, 0.45f}) {
    const FrameImage rough = test::render(test::sceneFromJson(wallScene(r, 64).dump()), 2).image;
    const int width = edgeWidth(rough, kFloorRow);
    EXPECT_GT(width, previous + 1) << "roughness " << r;
    std::printf("roughness %.2f: edge %d px\n", r, width);
    previous = width;
  }
}

TEST(GlossyReflection, RoughFloorUnderAUniformSkyKeepsItsLight) {
  // Every drawn direction sees the background: a floor of reflectivity 1 is
  // the background at any roughness, as the mirror is.
  json j = wallScene(0.7f, 16);
  j["objects"].erase(1);
  j["background"] = {0.5, 0.25, 0.75};
  const FrameImage image = test::render(test::sceneFromJson(j.dump()), 2).image;
  const test::Rgb sky = test::pixelAt(image, 48, 2);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const test::Rgb p = test::pixelAt(image, x, y);
      ASSERT_TRUE(p.r == sky.r && p.g == sky.g && p.b == sky.b) << x << ", " << y;
    }
  }
}

TEST(GlossyReflection, RoughnessZeroIsTheMirrorAndDrawsNothing) {
  const Scene none = test::sceneFromJson(wallScene(std::nullopt, 4).dump());
  const Scene zero = test::sceneFromJson(wallScene(0.0f, 4).dump());
  EXPECT_FALSE(EffectPlan::derive(zero).glossyReflection);
  EXPECT_TRUE(EffectPlan::derive(test::sceneFromJson(wallScene(0.2f, 4).dump())).glossyReflection);
  const FrameResult a = test::render(none, 2), b = test::render(zero, 2);
  EXPECT_EQ(a.image.rgb, b.image.rgb);
  EXPECT_EQ(a.stats.reflection, b.stats.reflection);
}

TEST(GlossyReflection, SameBytesForAnyThreadsTilesAndPattern) {
  Scene scene = test::sceneFromJson(wallScene(0.3f, 4).dump());
  for (SamplePattern pattern : {SamplePattern::kRegular, SamplePattern::kJittered, SamplePattern::kAdaptive,
                                SamplePattern::kPerceptual}) {
    scene.frame.sampling.pattern = pattern;
    const FrameImage one = test::render(scene, 1, 64).image;
    const FrameImage split = test::render(scene, 2, 7).image;
    EXPECT_EQ(one.rgb, split.rgb) << enumWord(pattern);
  }
}

}  // namespace
}  // namespace glint
