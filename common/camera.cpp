#include "common/camera.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace glint {

Camera::Camera(const CameraSpec& spec, int width, int height)
    : eye_(spec.eye),
      width_(static_cast<float>(width)),
      height_(static_cast<float>(height)) {
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

}  // namespace glint
