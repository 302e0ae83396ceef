#pragma once

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/math/power.h"
#include "common/scene/texture.h"

namespace glint {

// Equal spot cones make a hard edge: the ramp this wide in cosine.
constexpr float kHardSpotEdge = 1e-4f;

// The shading functions (the direct light's phongAmbient, phongDiffuse,
// phongSpecular, attenuate and spotFactor; the textures' wrapped,
// wrappedIndex, imagePoint, bilinearCorner and bilinearBlend; the
// irradiance field's octahedralPoint, shBasis, cosineLobe, probeShare,
// probeVisibility and shIrradiance; path transport's lobeSum, diffuseAlbedo,
// specularWeight and lobesReflect; the emitters' angleOf and triangleIrradiance), from shading.glsl, which the raster's
// shaders compile too: read them there. Here GLSL's names are C++'s, in
// float.
namespace glsl {

using glm::ivec2;
using glm::vec2;
using glm::vec3;
constexpr float HARD_SPOT_EDGE = kHardSpotEdge;
constexpr int WRAP_MIRRORED_REPEAT = static_cast<int>(TextureWrap::kMirroredRepeat);
constexpr int WRAP_CLAMP_TO_EDGE = static_cast<int>(TextureWrap::kClampToEdge);
inline float pow(float x, float y) { return power(x, y); }  // the same bits on every machine
inline float floor(float x) { return std::floor(x); }
inline vec2 floor(vec2 v) { return glm::floor(v); }
inline float clamp(float x, float lo, float hi) { return std::clamp(x, lo, hi); }
inline int clamp(int x, int lo, int hi) { return std::clamp(x, lo, hi); }
inline float max(float a, float b) { return std::max(a, b); }
inline float min(float a, float b) { return std::min(a, b); }
inline float sqrt(float x) { return std::sqrt(x); }
inline float abs(float x) { return std::abs(x); }
inline vec3 abs(vec3 v) { return glm::abs(v); }
inline vec3 max(vec3 a, vec3 b) { return glm::max(a, b); }

#define SHARED inline
#include "common/scene/shading.glsl"
#undef SHARED

}  // namespace glsl

using glsl::attenuate;
using glsl::phongAmbient;
using glsl::phongDiffuse;
using glsl::phongSpecular;
using glsl::spotFactor;

}  // namespace glint
