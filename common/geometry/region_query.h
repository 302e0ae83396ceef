#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/geometry/bounds.h"
#include "common/geometry/bvh.h"
#include "common/geometry/geometry.h"

namespace glint {

// A convex polytope: the points x with dot(n, x) <= d for every plane
// (n, d) (n of unit length), given also by its corners and their box, which
// the query uses to separate it from a triangle's plane and from BVH boxes.
struct ConvexRegion {
  std::vector<glm::vec4> planes;  // xyz: outward unit normal n, w: d
  std::vector<glm::vec3> corners;
  // Corners a primitive may share without entering the region (a receiver's
  // own vertices, which its neighbours share): a primitive's vertex equal to
  // one of them counts as outside every plane that passes through it.
  std::vector<glm::vec3> shared;
  Bounds3 box;
  // Widens every separating test by this distance, so that rounding never
  // separates a primitive that touches the region.
  float slack = 0.0f;
  // planes[0] is the plane a receiver lies in (the region's base): a
  // primitive lying in it (within slack / 10) touches the base without
  // entering, so that a receiver's coplanar neighbours never count.
  bool openBase = false;
};

// The plane through `point` with normal n (any length), oriented so that
// `inside` is on its inner side: a ConvexRegion's plane.
glm::vec4 planeThrough(const glm::vec3& point, glm::vec3 n, const glm::vec3& inside);
// Sets a region's box from its corners and its slack from their magnitude
// (their rounding, with a wide margin).
void finishRegion(ConvexRegion& region);

// Whether primitive `prim` may reach into `region` (the separating planes
// primitivesInRegion asks of each primitive it finds).
bool primitiveInRegion(const Geometry& geometry, std::uint32_t prim, const ConvexRegion& region);

// The primitives other than `skip` that may reach into `region`: a
// conservative answer, from separating planes only (the region's own planes,
// a triangle's plane, a sphere's distance, a BVH box's faces). Empty proves
// that none does; a primitive listed may merely lie near it.
std::vector<std::uint32_t> primitivesInRegion(const Bvh& bvh, const Geometry& geometry,
                                              const ConvexRegion& region, std::uint32_t skip);

}  // namespace glint
