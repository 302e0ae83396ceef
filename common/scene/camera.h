#pragma once

#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/geometry/bounds.h"
#include "common/geometry/ray.h"

namespace glint {

// The scene's camera, as the user writes it.
// The widest vertical field of view, in degrees (the narrowest is any
// above 0).
constexpr float kMaxFovY = 179.0f;

struct CameraSpec {
  glm::vec3 eye{0.0f, 0.0f, 0.0f};
  glm::vec3 lookAt{0.0f, 0.0f, -1.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovY = 45.0f;  // degrees, vertical
  // A thin lens: its diameter (scene units; 0, a pinhole) and the distance
  // from the eye to the plane of sharp focus, along the view direction.
  float aperture = 0.0f;
  float focusDistance = 1.0f;
};

// What makes a camera unusable, as "field: what is wrong" ("up: must not be
// the zero vector"), or "" for a good camera. Fields are the scene format's.
std::string cameraProblem(const CameraSpec& spec);
// fov_y's range in words: "(0, 179]".
std::string fovRange();

// The camera moved along its viewing direction so that the sphere around
// `bounds` fills the narrower of the two fields of view (vertical fov_y, or
// the horizontal one of a frame width / height wide): look_at at the box's
// centre, the eye at the distance where the sphere touches the view's
// edges, up kept. A box of one point keeps the spec's distance.
CameraSpec fitCamera(const CameraSpec& spec, const Bounds3& bounds, float aspect);

// A pinhole camera that sees exactly what gluLookAt(eye, lookAt, up) with
// gluPerspective(fovY, width / height, ...) shows: square pixels, film
// position (x, y) in pixels from the top-left corner of the image, and the
// ray through (x + 0.5, y + 0.5) passes through the centre of pixel (x, y),
// where OpenGL samples it.
class Camera {
 public:
  Camera(const CameraSpec& spec, int width, int height);

  Ray generateRay(const glm::vec2& film) const;
  // Through a thin lens: from the point at `lens` (in [0, 1)^2, spread
  // uniformly over the lens's disc) towards where the pinhole ray meets the
  // plane of focus. With aperture 0, the pinhole ray.
  Ray generateRay(const glm::vec2& film, const glm::vec2& lens) const;
  // The diameter in pixels of the blur a point at `depth` along the view
  // direction makes (the circle of confusion); 0 for a pinhole.
  float circleOfConfusion(float depth) const;
  const glm::vec3& eye() const { return eye_; }

 private:
  glm::vec3 eye_;
  glm::vec3 forward_;  // unit, towards lookAt
  glm::vec3 right_;    // unit, image +x
  glm::vec3 up_;       // unit, image -y (film y grows downwards)
  float halfHeight_;   // tan(fovY / 2): film half-height at distance 1
  float halfWidth_;
  float width_;
  float height_;
  float aperture_;
  float focusDistance_;
};

}  // namespace glint
