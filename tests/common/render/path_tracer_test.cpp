// Path transport checked against answers known without it: a furnace whose
// radiance is a geometric series, a white furnace that returns exactly the
// light it receives, the direct light of one light that Whitted transport
// computes the same, the irradiance of a sphere and of a rectangle in closed
// form; and its pixels the same for any threads and tiles.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/base/file_source.h"
#include "common/render/bsdf.h"
#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;
constexpr double kPi = 3.14159265358979;

// The mean of every channel of every pixel.
double mean(const LinearImage& image) {
  double sum = 0.0;
  for (float v : image.rgb) sum += v;
  return sum / static_cast<double>(image.rgb.size());
}

// The camera inside a sphere whose material reflects `albedo` diffusely and
// emits 1: a path sees 1 + albedo + albedo^2 + ... (one term a bounce).
json furnace(double albedo, int maxBounces) {
  return {{"glint", 1},
          {"image", {{"width", 16}, {"height", 16}}},
          {"camera", {{"eye", {0, 0, 0}}, {"look_at", {0, 0, -1}}, {"fov_y", 90}}},
          {"sampling", {{"pattern", "jittered"}, {"samples", 64}}},
          {"tracing", {{"transport", "path"}, {"max_bounces", maxBounces}}},
          {"materials", {{"m", {{"color", {albedo, albedo, albedo}}, {"diffuse", 1}, {"emission", {1, 1, 1}}}}}},
          {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 2}, {"material", "m"}}}}};
}

TEST(PathTracer, AFurnaceSumsItsBouncesGeometrically) {
  for (const int bounces : {0, 1, 2, 64}) {
    const double expected = (1.0 - std::pow(0.5, bounces + 2)) / (1.0 - 0.5);  // sum of 0.5^k, k = 0 .. bounces + 1
    const double got = mean(test::renderLinearFrame(test::sceneFromJson(furnace(0.5, bounces).dump())));
    std::printf("max_bounces %d: %.5f, expected %.5f\n", bounces, got, expected);
    EXPECT_NEAR(got, expected, 0.01 * expected) << bounces;
  }
}

// Inside the furnace with roulette out of reach, every path takes exactly
// max_bounces bounces and samples the emitting sphere at each vertex.
TEST(PathTracer, CountsItsPathsBouncesAndLightSamples) {
  RayStats stats;
  test::renderLinearFrame(test::sceneFromJson(furnace(0.5, 2).dump()), stats);
  EXPECT_EQ(stats.paths, 16u * 16u * 64u);
  EXPECT_EQ(stats.primary, stats.paths);
  EXPECT_EQ(stats.reflection, 2 * stats.paths);
  EXPECT_EQ(stats.longestPath, 2u);
  EXPECT_EQ(stats.lightSamples, 3 * stats.paths);
  EXPECT_EQ(stats.nonFiniteSamples, 0u);
}

// A sphere of `material` under a uniform white sky (the background, radiance
// 1), seen from outside: a convex surface that loses no energy returns
// exactly 1 along every path, whatever its lobes.
double whiteFurnace(const json& material) {
  const json scene = {{"glint", 1},
                      {"image", {{"width", 24}, {"height", 24}}},
                      {"camera", {{"eye", {0, 0, 3}}, {"look_at", {0, 0, 0}}, {"fov_y", 30}}},
                      {"sampling", {{"pattern", "jittered"}, {"samples", 16}}},
                      {"tracing", {{"transport", "path"}, {"max_bounces", 8}}},
                      {"background", {1, 1, 1}},
                      {"materials", {{"m", material}}},
                      {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "m"}}}}};
  return mean(test::renderLinearFrame(test::sceneFromJson(scene.dump())));
}

TEST(PathTracer, AWhiteFurnaceReturnsTheLightItReceivesAndNeverMore) {
  EXPECT_NEAR(whiteFurnace({{"diffuse", 1}}), 1.0, 1e-5);
  EXPECT_NEAR(whiteFurnace({{"diffuse", 0}, {"reflectivity", 1}}), 1.0, 1e-5);
  EXPECT_NEAR(whiteFurnace({{"diffuse", 0.5}, {"reflectivity", 0.5}}), 1.0, 1e-5);
  // Inside the glass a path bounces until Russian roulette may end it: each
  // path that goes on is weighted up (1 / 0.95), so the mean is 1 within noise.
  EXPECT_NEAR(whiteFurnace({{"diffuse", 0}, {"transparency", 1}, {"ior", 1.5}}), 1.0, 0.01);
  // Terms that add up to 3 are renormalised to 1; the Phong and GGX lobes
  // lose what they send below the horizon (and GGX what a single bounce
  // off its microfacets misses), never gain.
  const double overbright = whiteFurnace({{"diffuse", 1}, {"specular", 1}, {"shininess", 10}, {"reflectivity", 1},
                                          {"roughness", 0.5}});
  std::printf("terms summing to 3: %.4f\n", overbright);
  EXPECT_LE(overbright, 1.0);
  EXPECT_GT(overbright, 0.8);
}

// The lobes' weights: a material whose terms add past 1 (the room's mirror:
// 0.08 + 0.8 + 0.8) has each divided by the same sum, so that they share
// exactly 1; one whose terms stay under 1 keeps them.
TEST(PathTracer, AnOverbrightMaterialsLobesShareOne) {
  Material mirror;
  mirror.diffuse = 0.1f;
  mirror.specular = 0.8f;
  mirror.reflectivity = 0.8f;
  const LobeWeights w = lobeWeights(mirror, glm::vec3(0.8f));
  const float sum = 0.08f + 0.8f + 0.8f;
  EXPECT_NEAR(w.albedo.x, 0.08f / sum, 1e-6f);
  EXPECT_NEAR(w.specular, 0.8f / sum, 1e-6f);
  EXPECT_NEAR(w.reflectivity, 0.8f / sum, 1e-6f);
  EXPECT_NEAR(w.albedo.x + w.specular + w.reflectivity + w.transparency, 1.0f, 1e-6f);
  Material clay;
  clay.diffuse = 0.8f;
  clay.specular = 0.2f;
  const LobeWeights c = lobeWeights(clay, glm::vec3(0.8f, 0.35f, 0.25f));
  EXPECT_FLOAT_EQ(c.albedo.x, 0.64f);
  EXPECT_FLOAT_EQ(c.specular, 0.2f);
}

// A diffuse square under one light, in both transports (nothing else to
// bounce off: the path's light is all direct).
json litSquare(const json& light, const char* transport) {
  return {{"glint", 1},
          {"image", {{"width", 32}, {"height", 32}, {"encoding", "linear"}}},
          {"camera", {{"eye", {0, 3, 0.001}}, {"look_at", {0, 0, 0}}, {"fov_y", 60}}},
          {"sampling", {{"pattern", "jittered"}, {"samples", 16}}},
          {"tracing", {{"transport", transport}}},
          {"materials", {{"m", {{"color", {0.8, 0.6, 0.4}}, {"diffuse", 0.9}}}}},
          {"lights", {light}},
          {"objects", {{{"type", "quad"}, {"corners", {{-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}}}, {"material", "m"}}}}};
}

double largestDifference(const LinearImage& a, const LinearImage& b) {
  double most = 0.0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) most = std::max(most, std::abs(double(a.rgb[i]) - b.rgb[i]));
  return most;
}

TEST(PathTracer, OneLightOnADiffuseSurfaceIsWhittedsDirectLight) {
  const json lights[] = {
      {{"type", "point"}, {"position", {0.5, 1.5, 0.2}}, {"attenuation", {0.2, 0.1, 0.3}}},
      {{"type", "spot"}, {"position", {0, 2, 0}}, {"direction", {0.2, -1, 0}}, {"inner_angle", 15}, {"outer_angle", 35}},
      {{"type", "directional"}, {"direction", {-0.3, -1, 0.2}}, {"color", {0.7, 0.7, 0.7}}}};
  for (const json& light : lights) {
    const LinearImage whitted = test::renderLinearFrame(test::sceneFromJson(litSquare(light, "whitted").dump()));
    const LinearImage path = test::renderLinearFrame(test::sceneFromJson(litSquare(light, "path").dump()));
    EXPECT_GT(mean(whitted), 0.05) << light["type"];
    EXPECT_LT(largestDifference(whitted, path), 1e-5) << light["type"];
  }
}

// The radiance leaving a diffuse surface of albedo rho at the centre of the
// image, straight below a light; Lambertian: rho / pi x irradiance.
double centre(const LinearImage& image) {
  const std::size_t i = 3 * (static_cast<std::size_t>(image.height / 2) * image.width + image.width / 2);
  return image.rgb[i];
}

TEST(PathTracer, ASphereLightsLikeThePointAtItsCentre) {
  // A sphere of radius r and radiance color / r^2 gives a point facing it
  // at distance D the irradiance pi color / D^2 (a point light's, times pi).
  const json light = {{"type", "sphere"}, {"position", {0, 1.5, 0}}, {"radius", 0.4}};
  json scene = litSquare(light, "path");
  scene["image"] = {{"width", 33}, {"height", 33}, {"encoding", "linear"}};
  scene["sampling"]["samples"] = 256;
  const double got = centre(test::renderLinearFrame(test::sceneFromJson(scene.dump())));
  const double expected = 0.8 * 0.9 / (1.5 * 1.5);
  std::printf("sphere light: %.5f, expected %.5f\n", got, expected);
  EXPECT_NEAR(got, expected, 0.01 * expected);
}

// The form factor from a point to a parallel rectangle a x b at height c
// above one of its corners (Howell's catalogue, configuration B-3).
double cornerFormFactor(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * kPi);
}

TEST(PathTracer, AnAreaLightGivesTheRectanglesClosedFormIrradiance) {
  // A 1.2 x 0.8 light 1 above the centre: radiance pi color / area, the
  // irradiance pi L F with F four corner rectangles' form factors.
  const json light = {{"type", "area"}, {"position", {0, 1, 0}}, {"u", {1.2, 0, 0}}, {"v", {0, 0, 0.8}}};
  json scene = litSquare(light, "path");
  scene["image"] = {{"width", 33}, {"height", 33}, {"encoding", "linear"}};
  scene["sampling"]["samples"] = 1024;
  const double got = centre(test::renderLinearFrame(test::sceneFromJson(scene.dump())));
  const double radiance = kPi / (1.2 * 0.8);
  const double irradiance = kPi * radiance * 4 * cornerFormFactor(0.6, 0.4, 1.0);
  const double expected = 0.8 * 0.9 / kPi * irradiance;
  std::printf("area light: %.5f, expected %.5f\n", got, expected);
  EXPECT_NEAR(got, expected, 0.02 * expected);
}

// A flat Radiance HDR of w x h texels, each `upper` in the rows above the
// horizon and `lower` below (RGBE bytes over 128, exponent byte 129).
std::string skyHdr(int w, int h, int upper, int lower) {
  std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(h) + " +X " + std::to_string(w) + "\n";
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) bytes += std::string(3, static_cast<char>(y < h / 2 ? upper : lower)) + '\x81';
  }
  return bytes;
}

LinearImage renderUnderSky(const json& scene, const std::string& hdr) {
  MemorySource files;
  files.add("sky.hdr", hdr);
  return test::renderLinearFrame(loadScene(scene.dump(), files));
}

// A diffuse surface facing up under a sky of radiance 1 above the horizon
// and black below receives the irradiance pi: it sends its albedo. The sky
// is drawn by its luminance (the black half never) and weighed against the
// cosine lobe; either alone would give the same mean.
TEST(PathTracer, UnderAnEvenSkyADiffuseSurfaceSendsItsAlbedo) {
  json scene = litSquare(json::object(), "path");
  scene.erase("lights");
  scene["image"] = {{"width", 33}, {"height", 33}, {"encoding", "linear"}};
  scene["sampling"]["samples"] = 256;
  scene["environment"] = {{"file", "sky.hdr"}};
  const LinearImage image = renderUnderSky(scene, skyHdr(64, 32, 128, 0));
  const std::size_t i = 3 * (static_cast<std::size_t>(image.height / 2) * image.width + image.width / 2);
  std::printf("under the half sky: %.4f %.4f %.4f, expected 0.72 0.54 0.36\n", image.rgb[i], image.rgb[i + 1],
              image.rgb[i + 2]);
  EXPECT_NEAR(image.rgb[i], 0.8 * 0.9, 0.01);
  EXPECT_NEAR(image.rgb[i + 1], 0.6 * 0.9, 0.01);
  EXPECT_NEAR(image.rgb[i + 2], 0.4 * 0.9, 0.01);
  // A white sphere in a sky of 1 everywhere: the white furnace again, now
  // with the sky sampled as a light.
  json furnace = {{"glint", 1},
                  {"image", {{"width", 24}, {"height", 24}}},
                  {"camera", {{"eye", {0, 0, 3}}, {"look_at", {0, 0, 0}}, {"fov_y", 30}}},
                  {"sampling", {{"pattern", "jittered"}, {"samples", 16}}},
                  {"tracing", {{"transport", "path"}}},
                  {"environment", {{"file", "sky.hdr"}}},
                  {"materials", {{"m", {{"diffuse", 1}}}}},
                  {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "m"}}}}};
  EXPECT_NEAR(mean(renderUnderSky(furnace, skyHdr(64, 32, 128, 128))), 1.0, 0.01);
}

TEST(PathTracer, PixelsAreTheSameForAnyThreadsAndTiles) {
  Scene scene = loadSceneFile(test::sourcePath("scenes/cornell.json"));
  scene.frame.width = 48;
  scene.frame.height = 40;
  scene.frame.sampling.samples = 4;
  const FrameImage one = test::render(scene, 1, 32).image;
  const FrameImage two = test::render(scene, 2, 7).image;
  EXPECT_EQ(one.rgb, two.rgb);
}

}  // namespace
}  // namespace glint
