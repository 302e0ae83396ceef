#pragma once

#include <array>
#include <string_view>
#include <utility>

#include <glm/vec3.hpp>

#include "common/base/enum_words.h"

namespace glint {

enum class LightType { kPoint, kArea, kSpot, kDirectional, kSphere };

template <>
struct EnumWords<LightType> {
  static constexpr std::array<std::pair<LightType, std::string_view>, 5> kWords{
      {{LightType::kPoint, "point"},
       {LightType::kArea, "area"},
       {LightType::kSpot, "spot"},
       {LightType::kDirectional, "directional"},
       {LightType::kSphere, "sphere"}}};
};

// A light of the scene. Intensity at distance d: color / (c + l d + q d^2).
//  - point: at `position`.
//  - area: a parallelogram centred at `position` with full edge vectors `u`
//    and `v`, lighting the side u x v points to, as `samples` point lights of
//    color / samples each (common/render/area_light.h says where).
//  - spot: a point light whose light is scaled by spotFactor()
//    (common/scene/shading.h) of the angle off its axis `direction`: 1
//    inside the inner cone, 0 outside the outer one.
//  - directional: parallel light travelling along `direction`, the same
//    `color` everywhere (no position, no attenuation).
//  - sphere: a ball of `radius` around `position`, lighting every side: a
//    point light at its centre, unshadowed, times the share of the ball a
//    point sees, measured with `samples` shadow rays
//    (common/render/sphere_light.h says where they go).
// Area and sphere lights are soft: their shadows are measured with shadow
// rays to many points, not with one ray or a shadow map.
struct Light {
  LightType type = LightType::kPoint;
  glm::vec3 position{0.0f};
  glm::vec3 color{1.0f};
  glm::vec3 attenuation{1.0f, 0.0f, 0.0f};  // c, l, q
  glm::vec3 u{0.0f};
  glm::vec3 v{0.0f};
  int samples = 16;
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit: a spot's axis, a directional light's travel
  float cosInner = 1.0f;                   // a spot's cones: cosines of their half-angles
  float cosOuter = 0.70710678f;
  float radius = 0.0f;  // a sphere light's
};

inline bool softLight(const Light& l) {
  return l.type == LightType::kArea || l.type == LightType::kSphere;
}

// The shadow rays a soft light takes per query: the frame's light_samples
// when set (above 0), else the light's own.
inline int softLightSamples(const Light& l, int frameLightSamples) {
  return frameLightSamples > 0 ? frameLightSamples : l.samples;
}

}  // namespace glint
