#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/geometry/geometry.h"
#include "common/render/effects.h"
#include "common/scene/scene.h"

namespace glint {

// A material's colour at a surface point, as every transport reads it: the
// colour times the texture (glTF's baseColorFactor x baseColorTexture; a
// textured material's colour is 1 unless given, and 1 x t is t exactly), and
// a mesh's vertex colours times both (glTF's COLOR_0) where the scene has them.
inline glm::vec3 surfaceColor(const Scene& scene, const Material& m, const MaterialEffects& e, const SurfaceHit& s,
                              bool vertexColors) {
  const glm::vec3 base = e.textured && m.texture >= 0 ? m.color * scene.textures[m.texture].evaluate(s.uv) : m.color;
  return vertexColors ? base * s.color : base;
}

// A material's own light at uv: emission times the emission texture.
inline glm::vec3 surfaceEmission(const Scene& scene, const Material& m, const glm::vec2& uv) {
  return m.emissionTexture >= 0 ? m.emission * scene.textures[m.emissionTexture].evaluate(uv) : m.emission;
}

}  // namespace glint
