#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/scene/scene.h"

namespace glint::gl {

// Where on a primitive a light may be blocked: a convex set given by its
// corners that holds every point of the primitive the light may not reach.
// On a triangle, a rectangle in its plane (four corners); on a sphere, its
// bounding box (eight).
struct ShadowSpot {
  std::uint32_t prim = 0;  // primitive id: triangles first, then spheres
  int light = 0;
  std::array<glm::vec3, 8> corners{};
  int cornerCount = 0;
  // A triangle's plane: unit normal (xyz) and offset (w); zero for a sphere.
  glm::vec4 plane{0.0f};
};

// Which lights provably reach every point of each primitive, proved from the
// scene's geometry (not from a shadow map), and where on the others the
// light may be blocked, so that the raster pass reads the maps only there:
// on a software rasterizer one shadow-map fetch a fragment costs more than
// all the rest of the shading.
//
// A light reaches all of a triangle when nothing enters the tetrahedron
// between the light and the triangle (its neighbours may touch it at the
// corners they share, and anything lying in the triangle's plane touches
// only its base), and all of a sphere's lit side when nothing enters a
// square pyramid from the light around the sphere, up to the plane through
// its centre (common/geometry/region_query.h). What does enter a triangle's
// tetrahedron, projected from the light onto the triangle's plane, bounds
// its spot. The answer is conservative throughout. A directional light's
// spots are its primitives whole.
struct LightProof {
  // One per casting light and primitive it is not proved to reach, ordered
  // by light, then primitive.
  std::vector<ShadowSpot> spots;

  // Proves the lights `casts` flags (the others get no spots).
  static LightProof prove(const Scene& scene, const std::vector<bool>& casts);
};

}  // namespace glint::gl
