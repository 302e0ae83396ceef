// The hard-case scenes of scenes/hard, rendered end to end; every pixel is
// checked against a value computed here in double precision.
#include <cmath>
#include <functional>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_projection.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

// The ray through the centre of pixel (x, y), by unprojecting the window
// point with OpenGL's own matrices (glm's gluLookAt / gluPerspective / gluUnProject).
struct DRay {
  glm::dvec3 o, d;
};
DRay pixelRay(const Scene& s, int x, int y) {
  const glm::dvec3 eye(s.frame.camera.eye), target(s.frame.camera.lookAt), up(s.frame.camera.up);
  const glm::dmat4 view = glm::lookAt(eye, target, up);
  const double distance = glm::length(target - eye);
  const glm::dmat4 proj = glm::perspective(glm::radians(double(s.frame.camera.fovY)), double(s.frame.width) / s.frame.height,
                                           distance * 1e-3, distance * 10.0);
  const glm::dvec4 viewport(0, 0, s.frame.width, s.frame.height);
  const glm::dvec3 window(x + 0.5, s.frame.height - (y + 0.5), 0.5);
  const glm::dvec3 p = glm::unProject(window, view, proj, viewport);
  return {eye, glm::normalize(p - eye)};
}

using Expect = std::function<std::optional<glm::dvec3>(const DRay&)>;

// Compares every pixel whose expectation is decided (not nullopt) to +-1/255.
int expectPixels(const Scene& s, const FrameImage& image, const Expect& expected) {
  int compared = 0;
  for (int y = 0; y < s.frame.height; ++y) {
    for (int x = 0; x < s.frame.width; ++x) {
      const auto e = expected(pixelRay(s, x, y));
      if (!e) continue;
      const glm::dvec3 want = glm::clamp(*e, 0.0, 1.0) * 255.0;
      const test::Rgb got = test::pixelAt(image, x, y);
      EXPECT_NEAR(got.r, want.r, 1.01) << x << "," << y;
      EXPECT_NEAR(got.g, want.g, 1.01) << x << "," << y;
      EXPECT_NEAR(got.b, want.b, 1.01) << x << "," << y;
      ++compared;
    }
  }
  return compared;
}

Scene hardScene(const char* name) { return loadSceneFile(test::sourcePath(std::string("scenes/hard/") + name)); }

TEST(HardScenes, TotalInternalReflectionPrism) {
  const Scene s = hardScene("tir-prism.json");
  const FrameResult r = test::render(s, 2);
  const glm::dvec3 ceiling(0.2, 0.9, 0.5);
  const int n = expectPixels(s, r.image, [&](const DRay& ray) -> std::optional<glm::dvec3> {
    const double t = -ray.o.z / ray.d.z;  // the front face, z = 0
    const glm::dvec3 p = ray.o + t * ray.d;
    // Away from the edges, where a slanted ray could meet another face first.
    if (std::abs(p.x) > 0.8 || p.y < 0.1 || p.y > 0.9) return std::nullopt;
    return 0.9 * 0.9 * 0.9 * ceiling;  // in, totally reflected, out
  });
  EXPECT_GT(n, s.frame.width * s.frame.height * 2 / 3);
  EXPECT_EQ(r.stats.nonFiniteSamples, 0u);
}

TEST(HardScenes, ClosedMeshSeenThroughEdgesAndVertices) {
  const Scene s = hardScene("closed-mesh.json");
  const FrameResult r = test::render(s, 2);
  // |x| + |y| + |z| <= k along the ray: clip against the 8 half-spaces.
  const auto hits = [](const DRay& ray, double k) {
    double t0 = 0.0, t1 = 1e30;
    for (int i = 0; i < 8; ++i) {
      const glm::dvec3 n(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
      const double no = glm::dot(n, ray.o), nd = glm::dot(n, ray.d);
      if (nd == 0.0) {
        if (no > k) return false;
        continue;
      }
      const double t = (k - no) / nd;
      if (nd < 0.0) t0 = std::max(t0, t); else t1 = std::min(t1, t);
    }
    return t0 <= t1;
  };
  const int n = expectPixels(s, r.image, [&](const DRay& ray) -> std::optional<glm::dvec3> {
    const bool inner = hits(ray, 0.99), outer = hits(ray, 1.01);
    if (inner != outer) return std::nullopt;  // within 1 % of the silhouette
    return inner ? glm::dvec3(1.0, 0.5, 0.25) : glm::dvec3(0.0, 0.0, 0.2);
  });
  EXPECT_GT(n, s.frame.width * s.frame.height * 9 / 10);
}

TEST(HardScenes, LitPlaneFarFromOrigin) {
  const Scene s = hardScene("far-plane.json");
  const FrameResult r = test::render(s, 2);
  const glm::dvec3 light(10, 100040, 10);
  const int n = expectPixels(s, r.image, [&](const DRay& ray) -> std::optional<glm::dvec3> {
    const double t = (100000.0 - ray.o.y) / ray.d.y;
    const glm::dvec3 p = ray.o + t * ray.d;
    const double nl = std::max(0.0, glm::normalize(light - p).y);
    return glm::dvec3(0.9 * 0.1 + 0.9 * 0.8 * nl);
  });
  EXPECT_EQ(n, s.frame.width * s.frame.height);
  EXPECT_EQ(r.stats.shadowBlocked, 0u);
}

TEST(HardScenes, TinySphereFarAway) {
  const Scene s = hardScene("tiny-sphere.json");
  const FrameResult r = test::render(s, 2);
  const glm::dvec3 centre(0, 0, -50);
  const double radius = 1e-3;
  int hits = 0;
  const int n = expectPixels(s, r.image, [&](const DRay& ray) -> std::optional<glm::dvec3> {
    const glm::dvec3 f = centre - ray.o;
    const double miss = glm::length(f - glm::dot(f, ray.d) * ray.d);  // closest approach
    if (std::abs(miss - radius) < 0.1 * radius) return std::nullopt;
    hits += miss < radius ? 1 : 0;
    return miss < radius ? glm::dvec3(1.0, 0.5, 0.25) : glm::dvec3(0.0, 0.0, 0.2);
  });
  EXPECT_GT(n, s.frame.width * s.frame.height * 3 / 4);
  EXPECT_GT(hits, 500);
}

// Cases where a careless tracer produces NaN: every sample stays finite.
TEST(HardScenes, NoNonFiniteSamples) {
  using nlohmann::json;
  // Grazing rays over a mirror-like plane, the camera a hair above it.
  const json grazing = {
      {"glint", 1}, {"image", {{"width", 64}, {"height", 48}}},
      {"camera", {{"eye", {0, 1e-3, 0}}, {"look_at", {0, 1e-3, -10}}}},
      {"materials", {{"m", {{"ambient", 0.2}, {"reflectivity", 0.5}}}}},
      {"lights", {{{"type", "point"}, {"position", {0, 5, -5}}}}},
      {"objects", {{{"type", "quad"}, {"corners", {{-1e4, 0, 1e4}, {1e4, 0, 1e4}, {1e4, 0, -1e4}, {-1e4, 0, -1e4}}}, {"material", "m"}}}}};
  EXPECT_EQ(test::render(test::sceneFromJson(grazing.dump()), 2).stats.nonFiniteSamples, 0u);

  // Total internal reflection right at the depth limit.
  for (int depth : {2, 3, 4}) {
    Scene prism = hardScene("tir-prism.json");
    prism.frame.tracing.maxDepth = depth;
    EXPECT_EQ(test::render(prism, 2).stats.nonFiniteSamples, 0u) << depth;
  }

  // Zero-length vertex normals fall back to the geometric normal: the same
  // image as the same quad with no normals at all.
  json flat = {{"glint", 1}, {"image", {{"width", 32}, {"height", 32}}},
               {"camera", {{"eye", {0, 2, 3}}, {"look_at", {0, 0, 0}}}},
               {"materials", {{"m", {{"ambient", 0.1}, {"specular", 0.5}, {"shininess", 10}}}}},
               {"lights", {{{"type", "point"}, {"position", {1, 3, 1}}}}},
               {"objects", {{{"type", "mesh"}, {"positions", {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1}},
                             {"indices", {0, 2, 1, 0, 3, 2}}, {"material", "m"}}}}};
  const FrameResult plain = test::render(test::sceneFromJson(flat.dump()), 2);
  flat["objects"][0]["normals"] = json::array({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  const FrameResult zero = test::render(test::sceneFromJson(flat.dump()), 2);
  EXPECT_EQ(plain.image.rgb, zero.image.rgb);
  EXPECT_EQ(zero.stats.nonFiniteSamples, 0u);
}

// The same small scene near the origin and 1e5 away gives (nearly) the same
// image, with no non-finite sample.
TEST(HardScenes, CameraFarFromOrigin) {
  using nlohmann::json;
  const auto scene = [](double shift) {
    return json{{"glint", 1}, {"image", {{"width", 64}, {"height", 48}}},
                {"camera", {{"eye", {shift, 1.5, 4}}, {"look_at", {shift, 0.5, 0}}}},
                {"materials", {{"floor", {{"ambient", 0.1}, {"reflectivity", 0.3}}},
                               {"ball", {{"color", {1, 0.6, 0.2}}, {"ambient", 0.1}, {"specular", 0.4}, {"shininess", 30}}}}},
                {"lights", {{{"type", "point"}, {"position", {shift + 2, 4, 3}}}}},
                {"objects", {{{"type", "quad"}, {"corners", {{shift - 5, 0, 5}, {shift + 5, 0, 5}, {shift + 5, 0, -5}, {shift - 5, 0, -5}}}, {"material", "floor"}},
                             {{"type", "sphere"}, {"center", {shift, 0.5, 0}}, {"radius", 0.5}, {"material", "ball"}}}}};
  };
  const FrameResult near = test::render(test::sceneFromJson(scene(0.0).dump()), 2);
  const FrameResult far = test::render(test::sceneFromJson(scene(1e5).dump()), 2);
  EXPECT_EQ(far.stats.nonFiniteSamples, 0u);
  std::size_t close = 0;
  for (std::size_t i = 0; i < near.image.rgb.size(); ++i) close += std::abs(near.image.rgb[i] - far.image.rgb[i]) <= 3;
  EXPECT_GT(close, near.image.rgb.size() * 95 / 100);
}

}  // namespace
}  // namespace glint
