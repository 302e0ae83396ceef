#pragma once

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "common/math/power.h"

namespace glint {

// Equal spot cones make a hard edge: the ramp this wide in cosine.
constexpr float kHardSpotEdge = 1e-4f;

// The direct light's terms (phongAmbient, phongDiffuse, phongSpecular,
// attenuate, spotFactor), from shading.glsl, which the raster's shaders
// compile too: read them there. Here GLSL's names are C++'s, in float.
namespace glsl {

using glm::vec3;
constexpr float HARD_SPOT_EDGE = kHardSpotEdge;
inline float pow(float x, float y) { return power(x, y); }  // the same bits on every machine
inline float clamp(float x, float lo, float hi) { return std::clamp(x, lo, hi); }
inline float max(float a, float b) { return std::max(a, b); }

#define SHARED inline
#include "common/render/shading.glsl"
#undef SHARED

}  // namespace glsl

using glsl::attenuate;
using glsl::phongAmbient;
using glsl::phongDiffuse;
using glsl::phongSpecular;
using glsl::spotFactor;

}  // namespace glint
