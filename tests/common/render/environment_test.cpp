// The environment image: its equirectangular mapping and bilinear lookup
// against the scene format's definition worked out here in double
// precision, what escaping camera and mirror rays see in a rendered frame,
// exposure, hostile texels and directions, and the loader's refusals.
#include "common/scene/environment.h"

#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/base/error.h"
#include "common/base/file_source.h"
#include "common/base/thread_pool.h"
#include "common/render/effects.h"
#include "common/render/linear_frame.h"
#include "common/render/prepared_scene.h"
#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;
constexpr int kWidth = 16, kHeight = 8;

// The direction at (u, v) of the image, by the mapping's definition.
glm::dvec3 direction(double u, double v) {
  const double theta = v * kPi, phi = (u - 0.5) * 2.0 * kPi;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

// A texel's value in channel c, as a Radiance HDR byte over 128 (exact in
// RGBE with exponent byte 129): every texel and channel different.
int texelByte(int x, int y, int c) { return 8 + (x * 13 + y * 29 + c * 71) % 240; }
double texelValue(int x, int y, int c) { return texelByte(x, y, c) / 128.0; }

// A flat (not run-length encoded) Radiance HDR of those texels.
std::string skyHdr() {
  std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(kHeight) + " +X " +
                      std::to_string(kWidth) + "\n";
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      for (int c = 0; c < 3; ++c) bytes += static_cast<char>(texelByte(x, y, c));
      bytes += static_cast<char>(129);
    }
  }
  return bytes;
}

// The bilinear lookup the format defines, in double: texel centres at
// (i + 1/2) / size, wrapping in u, clamped in v.
glm::dvec3 expectedRadiance(const glm::dvec3& d, double scale = 1.0) {
  const glm::dvec3 n = glm::normalize(d);
  const double u = 0.5 + std::atan2(n.x, -n.z) / (2.0 * kPi);
  const double v = std::acos(std::clamp(n.y, -1.0, 1.0)) / kPi;
  const double x = u * kWidth - 0.5;
  const double y = std::clamp(v * kHeight - 0.5, 0.0, kHeight - 1.0);
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  glm::dvec3 r(0.0);
  for (int c = 0; c < 3; ++c) {
    const auto at = [&](int i, int j) { return texelValue((i % kWidth + kWidth) % kWidth, std::min(j, kHeight - 1), c); };
    const double top = at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx;
    const double bottom = at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx;
    r[c] = scale * (top * (1 - fy) + bottom * fy);
  }
  return r;
}

Environment skyEnvironment(float scale = 1.0f, float rotation = 0.0f) {
  std::vector<float> rgb;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      for (int c = 0; c < 3; ++c) rgb.push_back(static_cast<float>(texelValue(x, y, c)));
    }
  }
  return Environment(kWidth, kHeight, rgb, scale, rotation);
}

void expectNear(const glm::vec3& got, const glm::dvec3& want, double tolerance, const std::string& where) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tolerance * (1.0 + want[c])) << where << " channel " << c;
}

TEST(Environment, TexelCentresGiveTheirTexelsAndBetweenThemTheBilinearMix) {
  const Environment sky = skyEnvironment();
  int compared = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const glm::dvec3 centre = direction((x + 0.5) / kWidth, (y + 0.5) / kHeight);
      const glm::vec3 got = sky.radiance(glm::vec3(centre));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], texelValue(x, y, c), 2e-4) << x << ", " << y;
      // A quarter of a texel right and down, across the seam at u = 0 too.
      const glm::dvec3 between = direction((x + 0.75) / kWidth, (y + 0.75) / kHeight);
      expectNear(sky.radiance(glm::vec3(between)), expectedRadiance(between), 2e-4,
                 "between " + std::to_string(x) + ", " + std::to_string(y));
      compared += 2;
    }
  }
  EXPECT_EQ(compared, 2 * kWidth * kHeight);
}

TEST(Environment, TheMappingsAxesAreTheFormats) {
  const Environment sky = skyEnvironment();
  const auto texel = [](double u, double v) {
    const int x = static_cast<int>(u * kWidth), y = static_cast<int>(v * kHeight);
    return glm::dvec3(texelValue(x, y, 0), texelValue(x, y, 1), texelValue(x, y, 2));
  };
  // -z is the image's centre column, +x three quarters across, +z the seam;
  // straight up the top row's mix, straight down the bottom row's.
  expectNear(sky.radiance({0, 0, -1}), expectedRadiance({0, 0, -1}), 1e-5, "-z");
  expectNear(sky.radiance({0, 0, -1}), (texel(0.49, 0.49) + texel(0.51, 0.49) + texel(0.49, 0.51) + texel(0.51, 0.51)) / 4.0,
             1e-5, "-z as four texels");
  expectNear(sky.radiance({1, 0, 0}), (texel(0.74, 0.49) + texel(0.76, 0.49) + texel(0.74, 0.51) + texel(0.76, 0.51)) / 4.0,
             1e-5, "+x");
  expectNear(sky.radiance({0, 0, 1}), (texel(0.99, 0.49) + texel(0.01, 0.49) + texel(0.99, 0.51) + texel(0.01, 0.51)) / 4.0,
             1e-5, "+z across the seam");
  expectNear(sky.radiance({0, 1, 0}), expectedRadiance({0, 1, 0}), 1e-5, "up");
  expectNear(sky.radiance({0, -1, 0}), expectedRadiance({0, -1, 0}), 1e-5, "down");
  // Any length: the direction is what counts.
  EXPECT_EQ(sky.radiance({0.3f, 0.2f, -0.5f}), sky.radiance(glm::vec3(3.0f, 2.0f, -5.0f)));
}

TEST(Environment, HostileDirectionsAndTexelsStayFinite) {
  const Environment sky = skyEnvironment();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const glm::vec3 d : {glm::vec3(0.0f), glm::vec3(nan, 0, 1), glm::vec3(kInf, 0, 0), glm::vec3(0, -kInf, 1)}) {
    EXPECT_EQ(sky.radiance(d), glm::vec3(0.0f));
  }
  // The tiniest and the largest finite directions still find their texel.
  const float tiny = std::numeric_limits<float>::denorm_min(), huge = std::numeric_limits<float>::max();
  EXPECT_EQ(sky.radiance({0, 0, -tiny}), sky.radiance({0, 0, -1}));
  EXPECT_EQ(sky.radiance({0, 0, -huge}), sky.radiance({0, 0, -1}));
  EXPECT_EQ(sky.radiance({0, huge, 0}), sky.radiance({0, 1, 0}));
  // Texels that are not light: 0; a blinding one capped.
  const Environment bad(2, 1, {nan, -1.0f, kInf, 3e38f, 2.0f, -0.0f}, 1e10f);
  EXPECT_EQ(bad.texel(0, 0), glm::vec3(0.0f));
  EXPECT_EQ(bad.texel(1, 0), glm::vec3(Environment::kMaxRadiance, 2e10f, 0.0f));
  for (float u = 0.0f; u < 6.3f; u += 0.01f) {
    const glm::vec3 r = bad.radiance({std::sin(u), 0.1f, std::cos(u)});
    EXPECT_TRUE(std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z)) << u;
  }
}

// A scene of a mirror floor under the sky: camera rays that miss see the
// sky along their direction, those on the mirror the sky along the
// reflected one.
json mirrorScene(float exposure) {
  return {{"glint", 1},
          {"image", {{"width", 64}, {"height", 48}}},
          {"camera", {{"eye", {0, 1, 0}}, {"look_at", {0.3, 0.6, -1}}, {"fov_y", 90}}},
          {"background", {1, 0, 1}},
          {"environment", {{"file", "sky.hdr"}, {"exposure", exposure}}},
          {"materials", {{"mirror", {{"color", {0, 0, 0}}, {"ambient", 0}, {"diffuse", 0}, {"reflectivity", 1}}}}},
          {"objects", {{{"type", "quad"}, {"corners", {{-50, 0, -50}, {50, 0, -50}, {50, 0, 50}, {-50, 0, 50}}},
                        {"material", "mirror"}}}}};
}

Scene loadWithSky(const json& j, const std::string& file = skyHdr()) {
  MemorySource files;
  files.add("sky.hdr", file);
  return loadScene(j.dump(), files);
}

// Turned by theta about +y, the image shows along d what it showed along d
// turned back by theta.
TEST(Environment, ARotationTurnsTheImageAboutY) {
  constexpr double kDegrees = 75.0;
  const double theta = kDegrees * kPi / 180.0;
  const Environment turned = skyEnvironment(1.0f, static_cast<float>(theta));
  int compared = 0;
  for (double v = 0.03; v < 1.0; v += 0.07) {
    for (double u = 0.0; u < 1.0; u += 0.03) {
      const glm::dvec3 d = direction(u, v);
      const glm::dvec3 back(d.x * std::cos(theta) - d.z * std::sin(theta), d.y,
                            d.x * std::sin(theta) + d.z * std::cos(theta));
      expectNear(turned.radiance(glm::vec3(d)), expectedRadiance(back), 2e-4,
                 "u " + std::to_string(u) + ", v " + std::to_string(v));
      ++compared;
    }
  }
  EXPECT_GT(compared, 400);
  // By 90 degrees what lay along +z lies along +x.
  expectNear(skyEnvironment(1.0f, static_cast<float>(kPi / 2)).radiance({1, 0, 0}), expectedRadiance({0, 0, 1}), 1e-5,
             "+x after a quarter turn");
  // The scene's "rotation" in degrees is this turn.
  json j = mirrorScene(0.0f);
  j["environment"]["rotation"] = kDegrees;
  const Scene scene = loadWithSky(j);
  for (const glm::vec3 d : {glm::vec3(1, 0.2f, 0), glm::vec3(-0.3f, -0.5f, 0.8f), glm::vec3(0.1f, 0.9f, -0.2f)}) {
    EXPECT_EQ(scene.environment->radiance(d), turned.radiance(d));
  }
}

TEST(Environment, EscapingRaysSeeItBehindEverythingAndInTheMirror) {
  const Scene scene = loadWithSky(mirrorScene(0.0f));
  ASSERT_TRUE(EffectPlan::derive(scene).environment);
  const LinearImage image = test::renderLinearFrame(scene);
  const Camera camera(scene.frame.camera, scene.frame.width, scene.frame.height);
  int sky = 0, mirrored = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const Ray ray = camera.generateRay({x + 0.5f, y + 0.5f});
      glm::dvec3 d(ray.d);
      const double t = d.y < 0.0 ? -double(ray.o.y) / d.y : -1.0;
      const bool onMirror = t > 0.0 && std::abs(ray.o.x + t * d.x) < 50.0 && std::abs(ray.o.z + t * d.z) < 50.0;
      if (onMirror) d.y = -d.y;
      const std::size_t i = (static_cast<std::size_t>(y) * image.width + x) * 3;
      expectNear({image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]}, expectedRadiance(d), 1e-3,
                 "pixel " + std::to_string(x) + ", " + std::to_string(y));
      (onMirror ? mirrored : sky) += 1;
    }
  }
  EXPECT_GT(sky, 800);
  EXPECT_GT(mirrored, 800);
  // Every effect on renders what the plan asks for.
  EXPECT_EQ(test::render(scene, test::everyEffect(scene), 2).image.rgb, test::render(scene, 2).image.rgb);
  // Exposure 1 doubles every value, exactly.
  const LinearImage brighter = test::renderLinearFrame(loadWithSky(mirrorScene(1.0f)));
  for (std::size_t i = 0; i < image.rgb.size(); ++i) ASSERT_EQ(brighter.rgb[i], 2.0f * image.rgb[i]) << i;
}

TEST(Environment, SameBytesForAnyThreadsAndTiles) {
  json j = mirrorScene(0.0f);
  j["sampling"] = {{"pattern", "jittered"}, {"samples", 4}};
  j["materials"]["mirror"]["roughness"] = 0.3;
  j["objects"].push_back({{"type", "sphere"}, {"center", {0.5, 0.5, -2}}, {"radius", 0.5}, {"material", "mirror"}});
  const Scene scene = loadWithSky(j);
  EXPECT_EQ(test::render(scene, 1, 64).image.rgb, test::render(scene, 2, 7).image.rgb);
}

TEST(Environment, ASceneWithoutOneSeesItsBackground) {
  json j = mirrorScene(0.0f);
  j.erase("environment");
  const Scene scene = loadWithSky(j);
  EXPECT_FALSE(EffectPlan::derive(scene).environment);
  const LinearImage image = test::renderLinearFrame(scene);
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
    ASSERT_EQ(glm::vec3(image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]), glm::vec3(1, 0, 1)) << i / 3;
  }
}

TEST(Environment, BadEnvironmentsAreNamedErrors) {
  const auto refusal = [](const json& j, const std::string& file) {
    try {
      loadWithSky(j, file);
      return std::string("(loaded)");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  };
  json missing = mirrorScene(0.0f);
  missing["environment"]["file"] = "nowhere.hdr";
  EXPECT_NE(refusal(missing, skyHdr()).find("environment.file"), std::string::npos) << refusal(missing, skyHdr());
  EXPECT_NE(refusal(mirrorScene(0.0f), test::flatPng(4, 2)).find("not a Radiance HDR or OpenEXR image"),
            std::string::npos);
  const std::string vast = refusal(mirrorScene(0.0f), "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 30000 +X 30000\n");
  EXPECT_NE(vast.find("environment.file: image of 30000x30000 pixels is over the limit"), std::string::npos) << vast;
  EXPECT_NE(refusal(mirrorScene(40.0f), skyHdr()).find("environment.exposure"), std::string::npos);
  json extra = mirrorScene(0.0f);
  extra["environment"]["tilt"] = 90;
  EXPECT_NE(refusal(extra, skyHdr()).find("tilt"), std::string::npos);
  json spun = mirrorScene(0.0f);
  spun["environment"]["rotation"] = 400;
  EXPECT_NE(refusal(spun, skyHdr()).find("environment.rotation"), std::string::npos) << refusal(spun, skyHdr());
  json noFile = mirrorScene(0.0f);
  noFile["environment"].erase("file");
  EXPECT_NE(refusal(noFile, skyHdr()).find("environment.file"), std::string::npos) << refusal(noFile, skyHdr());
  // Its floats count against the scene's memory like any image's texels.
  MemorySource files;
  files.add("sky.hdr", skyHdr());
  LoadLimits small;
  small.maxTexturePixels = kWidth * kHeight - 1;
  try {
    loadScene(mirrorScene(0.0f).dump(), files, small);
    FAIL() << "an image over the texture limit loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("over the limit"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace glint
