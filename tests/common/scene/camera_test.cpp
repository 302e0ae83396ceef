#include "common/scene/camera.h"

#include <cmath>
#include <utility>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace glint {
namespace {

// The ray through (x + 0.5, y + 0.5) must project, through OpenGL's own
// gluLookAt / gluPerspective matrices and viewport transform, onto the centre
// of pixel (x, y) (window y grows upwards in GL, film y downwards).
TEST(Camera, PixelCentresMatchGluLookAtAndPerspective) {
  const CameraSpec spec{{0.3f, 1.6f, 5.2f}, {0.0f, 1.2f, 0.0f}, {0.0f, 1.0f, 0.0f}, 50.0f};
  const int w = 640, h = 480;
  const Camera camera(spec, w, h);
  const glm::mat4 view = glm::lookAt(spec.eye, spec.lookAt, spec.up);
  const glm::mat4 proj = glm::perspective(glm::radians(spec.fovY), float(w) / float(h), 0.1f, 100.0f);
  for (int y = 0; y < h; y += 37) {
    for (int x = 0; x < w; x += 41) {
      const Ray ray = camera.generateRay({x + 0.5f, y + 0.5f});
      EXPECT_NEAR(glm::length(ray.d), 1.0f, 1e-6f);
      const glm::vec4 clip = proj * view * glm::vec4(ray.o + 3.0f * ray.d, 1.0f);
      const glm::vec3 ndc = glm::vec3(clip) / clip.w;
      const float windowX = (ndc.x + 1.0f) * 0.5f * w;
      const float windowY = (ndc.y + 1.0f) * 0.5f * h;
      EXPECT_NEAR(windowX, x + 0.5f, 2e-3f);
      EXPECT_NEAR(h - windowY, y + 0.5f, 2e-3f);
    }
  }
}

TEST(Camera, ImageCentreLooksAtTarget) {
  const CameraSpec spec{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 45.0f};
  const Camera camera(spec, 100, 50);
  const Ray ray = camera.generateRay({50.0f, 25.0f});
  EXPECT_NEAR(ray.d.x, 0.0f, 1e-6f);
  EXPECT_NEAR(ray.d.y, 0.0f, 1e-6f);
  EXPECT_NEAR(ray.d.z, -1.0f, 1e-6f);
  // The top edge of the image is fov_y / 2 above the axis.
  const Ray top = camera.generateRay({50.0f, 0.0f});
  EXPECT_NEAR(std::atan2(top.d.y, -top.d.z), glm::radians(22.5f), 1e-5f);
}

// "fit": the camera keeps its direction, up and fov, looks at the box's
// centre, and the sphere around the box touches the narrower field of view:
// every corner projects inside the frame, and a point of the sphere on the
// view's edge projects onto the frame's edge.
TEST(Camera, FitFramesTheBoxFromTheCamerasDirection) {
  const Bounds3 box{{10.0f, -2.0f, 3.0f}, {14.0f, 1.0f, 4.0f}};
  for (const auto& [w, h] : {std::pair{640, 480}, std::pair{200, 600}}) {
    const CameraSpec spec{{0.0f, 0.0f, 0.0f}, {1.0f, 0.2f, -1.0f}, {0.0f, 1.0f, 0.0f}, 40.0f};
    const float aspect = static_cast<float>(w) / static_cast<float>(h);
    const CameraSpec fit = fitCamera(spec, box, aspect);
    EXPECT_NEAR(glm::distance(fit.lookAt, box.centre()), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(glm::normalize(fit.lookAt - fit.eye), glm::normalize(spec.lookAt - spec.eye)), 1.0f, 1e-6f);
    EXPECT_EQ(fit.up, spec.up);
    EXPECT_EQ(fit.fovY, spec.fovY);
    const glm::mat4 view = glm::lookAt(fit.eye, fit.lookAt, fit.up);
    const glm::mat4 proj = glm::perspective(glm::radians(fit.fovY), aspect, 0.1f, 1000.0f);
    for (const glm::vec3& corner : box.corners()) {
      const glm::vec4 clip = proj * view * glm::vec4(corner, 1.0f);
      EXPECT_LE(std::abs(clip.x / clip.w), 1.0f) << w << "x" << h;
      EXPECT_LE(std::abs(clip.y / clip.w), 1.0f) << w << "x" << h;
      EXPECT_GT(clip.w, 0.0f);
    }
    // The sphere's tangent point on the narrower side: at the field's edge.
    const double radius = 0.5 * glm::length(glm::dvec3(box.extent()));
    const double distance = glm::length(glm::dvec3(fit.eye) - glm::dvec3(box.centre()));
    const double halfV = glm::radians(40.0) / 2.0;
    const double halfH = std::atan(std::tan(halfV) * aspect);
    EXPECT_NEAR(std::asin(radius / distance), std::min(halfV, halfH), 1e-5) << w << "x" << h;
  }
}

// A box of one point: nothing to scale by, the camera keeps its distance.
TEST(Camera, FitAroundOnePointKeepsTheDistance) {
  const Bounds3 point{{1.0f, 2.0f, 3.0f}, {1.0f, 2.0f, 3.0f}};
  const CameraSpec spec{{0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 45.0f};
  const CameraSpec fit = fitCamera(spec, point, 1.0f);
  EXPECT_NEAR(glm::distance(fit.eye, glm::vec3(1.0f, 2.0f, 8.0f)), 0.0f, 1e-5f);
}

}  // namespace
}  // namespace glint
