#pragma once

#include <glm/vec3.hpp>

#include "common/math/lanes.h"

namespace glint {

// A ray o + t d. d is unit length for every ray the tracer makes; invD is
// 1/d per component, precomputed once per ray for the slab test (the thesis's
// "one division per ray instead of per box"). A zero component (+0.0 or
// -0.0) gives an infinity of the same sign, which the slab test relies on.
struct Ray {
  glm::vec3 o{0.0f};
  glm::vec3 d{0.0f, 0.0f, 1.0f};
  glm::vec3 invD{1.0f / 0.0f, 1.0f / 0.0f, 1.0f};

  Ray() = default;
  Ray(const glm::vec3& origin, const glm::vec3& direction) : o(origin), d(direction) {
    // The three divisions as one four-lane division: each lane rounds as the
    // scalar 1.0f / d would.
    const Float4 inverse = Float4{1.0f, 1.0f, 1.0f, 1.0f} / Float4{direction.x, direction.y, direction.z, 1.0f};
    invD = glm::vec3(inverse[0], inverse[1], inverse[2]);
  }
};

}  // namespace glint
