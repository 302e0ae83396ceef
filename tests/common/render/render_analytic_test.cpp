// End-to-end renders of scenes whose pixels the test computes on its own,
// in double precision, from the scene format's definitions.
#include <cmath>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;
constexpr int kSize = 64;
// Every scene here stores its light as it is ("encoding": "linear"), so that
// a byte is 255 x the analytic value.

json sphereScene(const json& material, const json& light) {
  return {{"glint", 1},
          {"image", {{"width", kSize}, {"height", kSize}, {"encoding", "linear"}}},
          {"camera", {{"eye", {0, 0, 6}}, {"look_at", {0, 0, 0}}, {"fov_y", 30}}},
          {"materials", {{"m", material}}},
          {"lights", {light}},
          {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "m"}}}}};
}

// Expected colour of pixel (x, y) of sphereScene, or nothing near the silhouette.
std::optional<glm::dvec3> expectedSpherePixel(int x, int y, const glm::dvec3& c, double ambient, double diffuse,
                                              double specular, double shininess, const glm::dvec3& lightPos,
                                              const glm::dvec3& att) {
  const double tanHalf = std::tan(15.0 * M_PI / 180.0);
  const double ndcX = 2.0 * (x + 0.5) / kSize - 1.0;
  const double ndcY = 1.0 - 2.0 * (y + 0.5) / kSize;
  const glm::dvec3 eye(0, 0, 6);
  const glm::dvec3 d = glm::normalize(glm::dvec3(ndcX * tanHalf, ndcY * tanHalf, -1.0));
  const double b = glm::dot(eye, d);
  const double disc = b * b - (glm::dot(eye, eye) - 1.0);
  if (std::abs(disc) < 0.02) return std::nullopt;
  if (disc < 0.0) return glm::dvec3(0.0);
  const double t = -b - std::sqrt(disc);
  const glm::dvec3 p = eye + t * d;
  const glm::dvec3 n = glm::normalize(p);
  const glm::dvec3 toLight = lightPos - p;
  const double dist = glm::length(toLight);
  const glm::dvec3 l = toLight / dist;
  glm::dvec3 color = c * ambient;
  const double nl = glm::dot(n, l);
  if (nl > 0.0) {
    const double li = 1.0 / (att.x + att.y * dist + att.z * dist * dist);
    color += li * c * diffuse * nl;
    const glm::dvec3 r = 2.0 * nl * n - l;
    const double vr = glm::dot(-d, r);
    if (vr > 0.0) color += glm::dvec3(li * specular * std::pow(vr, shininess));
  }
  return color;
}

void expectSphereMatches(double specular, double shininess, const glm::dvec3& att) {
  const glm::dvec3 c(1.0, 0.5, 0.25);
  const glm::dvec3 lightPos(3, 4, 5);
  const json material = {{"color", {1.0, 0.5, 0.25}}, {"ambient", 0.05}, {"diffuse", 0.7},
                         {"specular", specular}, {"shininess", shininess}};
  const json light = {{"type", "point"}, {"position", {3, 4, 5}}, {"attenuation", {att.x, att.y, att.z}}};
  const Scene scene = test::sceneFromJson(sphereScene(material, light).dump());
  const FrameImage image = test::render(scene).image;
  int compared = 0;
  int lit = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const auto e = expectedSpherePixel(x, y, c, 0.05, 0.7, specular, shininess, lightPos, att);
      if (!e) continue;
      const test::Rgb got = test::pixelAt(image, x, y);
      const glm::dvec3 want = glm::clamp(*e, 0.0, 1.0) * 255.0;
      ASSERT_NEAR(got.r, want.r, 1.0) << x << "," << y;
      ASSERT_NEAR(got.g, want.g, 1.0) << x << "," << y;
      ASSERT_NEAR(got.b, want.b, 1.0) << x << "," << y;
      ++compared;
      lit += got.g > 20 ? 1 : 0;
    }
  }
  EXPECT_GT(compared, kSize * kSize * 9 / 10);
  EXPECT_GT(lit, 500);
}

TEST(RenderAnalytic, DiffuseSphere) { expectSphereMatches(0.0, 1.0, {1, 0, 0}); }
TEST(RenderAnalytic, PhongHighlight) { expectSphereMatches(0.6, 30.0, {1, 0, 0}); }
TEST(RenderAnalytic, Attenuation) { expectSphereMatches(0.3, 10.0, {0.2, 0.05, 0.02}); }

// A mirror filling the view reflects a constant-coloured wall behind the
// camera: every pixel is reflectivity x the wall's colour.
TEST(RenderAnalytic, Mirror) {
  const json scene = {
      {"glint", 1},
      {"image", {{"width", 32}, {"height", 24}, {"encoding", "linear"}}},
      {"camera", {{"eye", {0, 0, 5}}, {"look_at", {0, 0, 0}}, {"fov_y", 40}}},
      {"materials",
       {{"mirror", {{"ambient", 0}, {"diffuse", 0}, {"reflectivity", 0.75}}},
        {"wall", {{"color", {0.4, 0.8, 1.0}}, {"ambient", 1}, {"diffuse", 0}}}}},
      {"objects",
       {{{"type", "quad"}, {"corners", {{-50, -50, 0}, {50, -50, 0}, {50, 50, 0}, {-50, 50, 0}}}, {"material", "mirror"}},
        {{"type", "quad"}, {"corners", {{-50, -50, 9}, {-50, 50, 9}, {50, 50, 9}, {50, -50, 9}}}, {"material", "wall"}}}}};
  const FrameResult result = test::render(test::sceneFromJson(scene.dump()));
  for (int y = 0; y < 24; ++y) {
    for (int x = 0; x < 32; ++x) {
      const test::Rgb p = test::pixelAt(result.image, x, y);
      ASSERT_NEAR(p.r, 0.75 * 0.4 * 255, 1.0);
      ASSERT_NEAR(p.g, 0.75 * 0.8 * 255, 1.0);
      ASSERT_NEAR(p.b, 0.75 * 1.0 * 255, 1.0);
    }
  }
  EXPECT_EQ(result.stats.reflection, 32u * 24u);
}

// u runs to the right and v up on a quad with uvs (0,0) (1,0) (1,1) (0,1):
// with scale 2, the top-left and bottom-right quarters are colour 1.
TEST(RenderAnalytic, CheckerOrientation) {
  const json scene = {
      {"glint", 1},
      {"image", {{"width", 40}, {"height", 40}, {"encoding", "linear"}}},
      {"camera", {{"eye", {0, 0, 3}}, {"look_at", {0, 0, 0}}, {"fov_y", 30}}},
      {"textures", {{"c", {{"type", "checker"}, {"colors", {{1, 0, 0}, {0, 0, 1}}}, {"scale", 2}}}}},
      {"materials", {{"m", {{"texture", "c"}, {"ambient", 1}, {"diffuse", 0}}}}},
      {"objects",
       {{{"type", "quad"},
         {"corners", {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}},
         {"uvs", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}},
         {"material", "m"}}}}};
  const FrameImage image = test::render(test::sceneFromJson(scene.dump())).image;
  EXPECT_EQ(test::pixelAt(image, 15, 15).b, 255);  // top-left: (0 + 1) mod 2 = 1
  EXPECT_EQ(test::pixelAt(image, 24, 15).r, 255);  // top-right: (1 + 1) mod 2 = 0
  EXPECT_EQ(test::pixelAt(image, 15, 24).r, 255);  // bottom-left: 0
  EXPECT_EQ(test::pixelAt(image, 24, 24).b, 255);  // bottom-right: 1
}

// A sphere between a point light and a floor: the floor point under it gets
// only ambient light, a point outside its shadow the full Lambert term.
TEST(RenderAnalytic, HardShadow) {
  const json scene = {
      {"glint", 1},
      {"image", {{"width", 80}, {"height", 60}, {"encoding", "linear"}}},
      {"camera", {{"eye", {0, 4, 4}}, {"look_at", {0, 0, 0}}, {"fov_y", 60}}},
      {"materials", {{"floor", {{"ambient", 0.2}, {"diffuse", 0.8}}}, {"ball", {{"color", {1, 0, 0}}}}}},
      {"lights", {{{"type", "point"}, {"position", {0, 5, 0}}}}},
      {"objects",
       {{{"type", "quad"}, {"corners", {{-9, 0, 9}, {9, 0, 9}, {9, 0, -9}, {-9, 0, -9}}}, {"material", "floor"}},
        {{"type", "sphere"}, {"center", {0, 1, 0}}, {"radius", 0.5}, {"material", "ball"}}}}};
  const Scene s = test::sceneFromJson(scene.dump());
  const FrameImage image = test::render(s).image;
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 4, 4), glm::vec3(0), glm::vec3(0, 1, 0));
  const glm::mat4 proj = glm::perspective(glm::radians(60.0f), 80.0f / 60.0f, 0.1f, 100.0f);
  const auto pixelOf = [&](const glm::vec3& p) {
    const glm::vec4 clip = proj * view * glm::vec4(p, 1.0f);
    const int x = static_cast<int>((clip.x / clip.w + 1.0f) * 0.5f * 80);
    const int y = 60 - 1 - static_cast<int>((clip.y / clip.w + 1.0f) * 0.5f * 60);
    return test::pixelAt(image, x, y);
  };
  EXPECT_EQ(pixelOf({0.0f, 0.0f, 0.05f}).g, 51);  // shadowed: 0.2 * 255
  const double lit = (0.2 + 0.8 * 5.0 / std::sqrt(1.5 * 1.5 + 25.0)) * 255.0;
  EXPECT_NEAR(pixelOf({1.5f, 0.0f, 0.0f}).g, lit, 3.0);
}

}  // namespace
}  // namespace glint
