#pragma once

#include <array>
#include <string_view>
#include <utility>

#include <glm/vec3.hpp>

#include "common/base/enum_words.h"

namespace glint {

enum class LightType { kPoint, kArea };

template <>
struct EnumWords<LightType> {
  static constexpr std::array<std::pair<LightType, std::string_view>, 2> kWords{
      {{LightType::kPoint, "point"}, {LightType::kArea, "area"}}};
};

// A light of the scene. Intensity at distance d: color / (c + l d + q d^2).
//  - point: at `position`.
//  - area: a parallelogram centred at `position` with full edge vectors `u`
//    and `v`, lighting the side u x v points to, as `samples` point lights of
//    color / samples each (common/render/area_light.h says where).
struct Light {
  LightType type = LightType::kPoint;
  glm::vec3 position{0.0f};
  glm::vec3 color{1.0f};
  glm::vec3 attenuation{1.0f, 0.0f, 0.0f};  // c, l, q
  glm::vec3 u{0.0f};
  glm::vec3 v{0.0f};
  int samples = 16;
};

}  // namespace glint
