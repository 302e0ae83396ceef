#pragma once

#include <cmath>

#include <glm/vec3.hpp>

namespace glint {

// True when every component is a finite number (no NaN, no infinity).
inline bool allFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace glint
