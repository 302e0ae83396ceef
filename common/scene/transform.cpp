#include "common/scene/transform.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "common/math/circular.h"

namespace glint {
namespace {

// glm::rotate(m, angle, v), the same operations in its order, but with the
// sine and cosine of sineCosine: glm takes them from std::sin and std::cos,
// which glibc picks at run time.
glm::mat4 rotate(const glm::mat4& m, float angle, const glm::vec3& v) {
  const SineCosine sc = sineCosine(angle);
  const float c = sc.cos;
  const float s = sc.sin;
  const glm::vec3 axis(glm::normalize(v));
  const glm::vec3 temp((1.0f - c) * axis);
  glm::mat3 rotation;  // glm's is a mat4 whose upper 3 x 3 alone it fills and reads
  rotation[0][0] = c + temp[0] * axis[0];
  rotation[0][1] = temp[0] * axis[1] + s * axis[2];
  rotation[0][2] = temp[0] * axis[2] - s * axis[1];
  rotation[1][0] = temp[1] * axis[0] - s * axis[2];
  rotation[1][1] = c + temp[1] * axis[1];
  rotation[1][2] = temp[1] * axis[2] + s * axis[0];
  rotation[2][0] = temp[2] * axis[0] + s * axis[1];
  rotation[2][1] = temp[2] * axis[1] - s * axis[0];
  rotation[2][2] = c + temp[2] * axis[2];
  glm::mat4 result;
  result[0] = m[0] * rotation[0][0] + m[1] * rotation[0][1] + m[2] * rotation[0][2];
  result[1] = m[0] * rotation[1][0] + m[1] * rotation[1][1] + m[2] * rotation[1][2];
  result[2] = m[0] * rotation[2][0] + m[1] * rotation[2][1] + m[2] * rotation[2][2];
  result[3] = m[3];
  return result;
}

}  // namespace

glm::mat4 Transform::matrix() const {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
  if (angleDegrees != 0.0f) m = rotate(m, glm::radians(angleDegrees), glm::normalize(axis));
  return glm::scale(m, scale);
}

glm::mat3 Transform::normalMatrix() const { return glm::transpose(glm::inverse(glm::mat3(matrix()))); }

}  // namespace glint
