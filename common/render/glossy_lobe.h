#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace glint {

// A rough reflector's lobe: the microfacet normal h is drawn from the GGX
// distribution D(h) cos(theta_h) around the shading normal (Walter, Marschner,
// Li and Torrance, "Microfacet Models for Refraction through Rough Surfaces",
// EGSR 2007, eq. 35-36), with alpha = roughness^2 as glTF's
// metallic-roughness model takes it; u in [0, 1)^2 picks h.
glm::vec3 ggxMicrofacetNormal(const glm::vec3& n, float alpha, const glm::vec2& u);

// The reflected ray of unit d off a material of `roughness` (> 0) with unit
// shading normal ns and geometric normal ng (both facing d's origin): d
// reflected about a microfacet normal drawn at u; a direction that would
// leave below the surface is mirrored back above its plane, so that every
// sample stays on the lit side and the lobe keeps the ray's whole weight.
glm::vec3 glossyDirection(const glm::vec3& d, const glm::vec3& ns, const glm::vec3& ng, float roughness,
                          const glm::vec2& u);

}  // namespace glint
