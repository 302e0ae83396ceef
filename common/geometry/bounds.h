#pragma once

#include <array>
#include <limits>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace glint {

// Axis-aligned box. A default box is empty (min = +inf, max = -inf), so a
// union needs no special case for the first element.
struct Bounds3 {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  glm::vec3 extent() const { return max - min; }
  glm::vec3 centre() const { return 0.5f * (min + max); }
  // p inside the box or on its boundary.
  bool contains(const glm::vec3& p) const {
    return p.x >= min.x && p.y >= min.y && p.z >= min.z && p.x <= max.x && p.y <= max.y && p.z <= max.z;
  }
  // The eight corners: corner i takes max.x where bit 0 of i is set, max.y
  // bit 1, max.z bit 2.
  std::array<glm::vec3, 8> corners() const {
    std::array<glm::vec3, 8> c;
    for (std::size_t i = 0; i < 8; ++i) c[i] = {i & 1 ? max.x : min.x, i & 2 ? max.y : min.y, i & 4 ? max.z : min.z};
    return c;
  }
  float surfaceArea() const;
  int longestAxis() const;
  void expand(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void expand(const Bounds3& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
};

}  // namespace glint
