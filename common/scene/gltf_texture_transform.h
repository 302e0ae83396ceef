#pragma once

#include <glm/vec2.hpp>

#include "common/scene/texture.h"

namespace glint {

// glTF's KHR_texture_transform of a texture: uv' = T(offset) R(rotation)
// S(scale) uv in glTF's texture space (v down from the image's top).
struct KhrTextureTransform {
  glm::dvec2 offset{0.0};
  double rotation = 0.0;  // radians: the uvs counter-clockwise, the image clockwise
  glm::dvec2 scale{1.0};
};

// The same map of Glint's uv (v up: glTF's v read as 1 - v, as Assimp
// imports it).
UvTransform glintUvTransform(const KhrTextureTransform& t);

}  // namespace glint
