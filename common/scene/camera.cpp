#include "common/scene/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "common/math/circular.h"
#include "common/math/finite.h"

namespace glint {

std::string fovRange() { return "(0, " + std::to_string(static_cast<int>(kMaxFovY)) + "]"; }

std::string cameraProblem(const CameraSpec& c) {
  if (!allFinite(c.eye)) return "eye: must be finite";
  if (!allFinite(c.lookAt)) return "look_at: must be finite";
  if (!allFinite(c.up)) return "up: must be finite";
  if (!(c.fovY > 0.0f && c.fovY <= kMaxFovY)) return "fov_y: must be in " + fovRange();
  if (!(c.aperture >= 0.0f && std::isfinite(c.aperture))) return "aperture: must be a finite number >= 0";
  if (!(c.focusDistance > 0.0f && std::isfinite(c.focusDistance))) return "focus_distance: must be a finite number > 0";
  const glm::vec3 forward = c.lookAt - c.eye;
  if (glm::dot(forward, forward) == 0.0f) return "look_at: must differ from camera.eye";
  if (glm::dot(c.up, c.up) == 0.0f) return "up: must not be the zero vector";
  const glm::vec3 side = glm::cross(glm::normalize(forward), glm::normalize(c.up));
  if (!(glm::length(side) > 1e-6f)) {
    return "up: is parallel to the viewing direction (look_at - eye); choose another up vector";
  }
  return "";
}

CameraSpec fitCamera(const CameraSpec& spec, const Bounds3& bounds, float aspect) {
  const float halfV = glm::radians(spec.fovY) * 0.5f;
  const float halfH = std::atan(std::tan(halfV) * aspect);
  const float radius = 0.5f * glm::length(bounds.extent());
  const glm::vec3 forward = glm::normalize(spec.lookAt - spec.eye);
  const float distance =
      radius > 0.0f ? radius / sineCosine(std::min(halfV, halfH)).sin : glm::length(spec.lookAt - spec.eye);
  CameraSpec out = spec;
  out.lookAt = bounds.centre();
  out.eye = out.lookAt - distance * forward;
  return out;
}

Camera::Camera(const CameraSpec& spec, int width, int height)
    : eye_(spec.eye),
      width_(static_cast<float>(width)),
      height_(static_cast<float>(height)),
      aperture_(spec.aperture),
      focusDistance_(spec.focusDistance) {
  // gluLookAt: f = normalize(center - eye), s = normalize(f x up), u = s x f.
  forward_ = glm::normalize(spec.lookAt - spec.eye);
  right_ = glm::normalize(glm::cross(forward_, spec.up));
  up_ = glm::cross(right_, forward_);
  halfHeight_ = std::tan(glm::radians(spec.fovY) * 0.5f);
  halfWidth_ = halfHeight_ * width_ / height_;
}

Ray Camera::generateRay(const glm::vec2& film) const {
  // Normalised device coordinates in [-1, 1], y up as in OpenGL.
  const float ndcX = 2.0f * film.x / width_ - 1.0f;
  const float ndcY = 1.0f - 2.0f * film.y / height_;
  const glm::vec3 d = forward_ + (ndcX * halfWidth_) * right_ + (ndcY * halfHeight_) * up_;
  return Ray(eye_, glm::normalize(d));
}

Ray Camera::generateRay(const glm::vec2& film, const glm::vec2& lens) const {
  const Ray pinhole = generateRay(film);
  if (aperture_ == 0.0f) return pinhole;
  const glm::vec3 focus = eye_ + (focusDistance_ / glm::dot(pinhole.d, forward_)) * pinhole.d;
  const float r = 0.5f * aperture_ * std::sqrt(lens.x);
  const SineCosine phi = sineCosine(6.28318530717958647692f * lens.y);
  const glm::vec3 origin = eye_ + (r * phi.cos) * right_ + (r * phi.sin) * up_;
  return Ray(origin, glm::normalize(focus - origin));
}

float Camera::circleOfConfusion(float depth) const {
  if (aperture_ == 0.0f || !(depth > 0.0f)) return 0.0f;
  // The blur's diameter on the plane of focus, over a pixel's size there.
  const float pixel = 2.0f * focusDistance_ * halfHeight_ / height_;
  return aperture_ * std::abs(depth - focusDistance_) / depth / pixel;
}

}  // namespace glint
