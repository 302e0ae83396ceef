#pragma once

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace glint {

// An object's transform from the scene: scale, then rotate (axis, angle in
// degrees), then translate.
struct Transform {
  glm::vec3 scale{1.0f};
  glm::vec3 axis{0.0f, 1.0f, 0.0f};
  float angleDegrees = 0.0f;
  glm::vec3 translate{0.0f};

  glm::mat4 matrix() const;
  // Normals transform by the inverse transpose (right for non-uniform scale).
  glm::mat3 normalMatrix() const;
  bool uniformScale() const { return scale.x == scale.y && scale.y == scale.z; }
};

}  // namespace glint
