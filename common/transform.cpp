#include "common/transform.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

namespace glint {

glm::mat4 Transform::matrix() const {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
  if (angleDegrees != 0.0f) m = glm::rotate(m, glm::radians(angleDegrees), glm::normalize(axis));
  return glm::scale(m, scale);
}

glm::mat3 Transform::normalMatrix() const { return glm::transpose(glm::inverse(glm::mat3(matrix()))); }

}  // namespace glint
