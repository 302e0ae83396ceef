#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/geometry/bounds.h"
#include "common/geometry/ray.h"
#include "common/geometry/sphere.h"
#include "common/geometry/triangle.h"

namespace glint {

// One scene object made of triangles (a mesh, a quad, a triangle): the
// thesis's "model", which holds the material for all its triangles.
struct Model {
  std::uint32_t material = 0;
};

// Three indices into the shared vertex list and the model they belong to.
// The indices are stored in ascending order: the intersection arithmetic is
// then the same for either winding, and sidedness is decided from the ray
// (face-forward normals), never from the stored order.
struct Triangle {
  std::array<std::uint32_t, 3> v;
  std::uint32_t model;
};

// A mesh as the scene gives it: positions and triangles, optional per-vertex
// normals, uvs and colours (empty when absent).
struct MeshInput {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;  // three per triangle
  std::uint32_t material = 0;
  std::vector<glm::vec3> colors;  // per vertex, times the material's colour (none: white)
};

// Nearest hit found by traversal: distance, primitive and (for triangles)
// the barycentric weights of the stored vertices.
struct Hit {
  float t;
  std::uint32_t prim;
  float b0;
  float b1;
  float b2;
};

// The order of hits along a ray: nearer first, and of two at exactly the same
// distance (a ray through a shared edge) the lower primitive id, so that the
// BVH and a brute-force loop agree on the hit whatever order they test in.
inline bool closerHit(const Hit& a, const Hit& b) {
  return a.t < b.t || (a.t == b.t && a.prim < b.prim);
}

// What shading needs to know about a hit point.
struct SurfaceHit {
  glm::vec3 p;   // hit point, reconstructed from the surface (not o + t d)
  glm::vec3 ng;  // unit geometric normal, facing the incoming ray
  glm::vec3 ns;  // unit shading normal, in the hemisphere of ng
  glm::vec2 uv;
  glm::vec3 color;  // the vertex colours' blend (white without them)
  // Bound on the rounding error of each coordinate of p (absolute): how far
  // a spawned ray's origin must move off the surface at least.
  float error;
};

// All primitives of a scene. Primitive ids number the triangles first, then
// the spheres. Triangles share one vertex list (position, normal, uv per
// vertex), as in the thesis; a mesh without normals is shaded flat with its
// geometric normals, one without uvs gets uv (0, 0).
class Geometry {
 public:
  void addMesh(MeshInput mesh);
  void addSphere(const Sphere& s) { spheres_.push_back(s); }

  std::uint32_t primitiveCount() const {
    return static_cast<std::uint32_t>(triangles_.size() + spheres_.size());
  }
  bool isSphere(std::uint32_t prim) const { return prim >= triangles_.size(); }
  Bounds3 primitiveBounds(std::uint32_t prim) const;
  // The box around every primitive (empty for a scene without any).
  Bounds3 bounds() const;
  std::optional<Hit> intersect(std::uint32_t prim, const Ray& ray, float tMax) const {
    return intersect(prim, ray, WatertightRay(ray), tMax);
  }
  std::optional<Hit> intersect(std::uint32_t prim, const Ray& ray, const WatertightRay& w, float tMax) const;
  // withUv false skips the texture coordinates (uv stays (0, 0)), and
  // withColor false the vertex colours (white): no work for a lookup that a
  // plain-coloured material never makes, or for colours no mesh has.
  SurfaceHit surface(const Ray& ray, const Hit& hit, bool withUv = true, bool withColor = true) const;
  // Where the shadow rays of a hit leave from (Hanika, "Hacking the Shadow
  // Terminator", Ray Tracing Gems II, 2021): s.p moved onto the curved
  // surface the triangle's vertex normals describe, so that the flat
  // triangles of a smooth mesh do not shadow the light their shading normals
  // catch. Each corner's tangent plane (its position, its unit normal turned
  // to s.ns's side) lifts the point onto it where the point lies below it;
  // the lifts are blended by the hit's barycentric weights. A flat triangle,
  // a saddle or concave corner and a sphere leave p where it is. `error`
  // bounds the moved point's rounding as SurfaceHit::error bounds p's.
  struct LiftedPoint {
    glm::vec3 p;
    float error;
  };
  LiftedPoint lifted(const Hit& hit, const SurfaceHit& s) const;
  std::uint32_t materialOf(std::uint32_t prim) const;

  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<Sphere>& spheres() const { return spheres_; }
  const std::vector<glm::vec3>& positions() const { return positions_; }
  const std::vector<glm::vec3>& normals() const { return normals_; }
  const std::vector<glm::vec2>& uvs() const { return uvs_; }
  // Every vertex's colour once a mesh has them (white for the others);
  // empty while none has.
  const std::vector<glm::vec3>& colors() const { return colors_; }
  // Unit geometric normal of each triangle, normalize(cross(b - a, c - a))
  // of its sorted vertices, computed once when the mesh is added.
  const std::vector<glm::vec3>& faceNormals() const { return faceNormals_; }
  const std::vector<Model>& models() const { return models_; }
  // Triangles left out because they cannot be hit: zero area, collinear or
  // repeated vertices, non-finite coordinates (kDroppedWhy, in words).
  std::size_t droppedTriangles() const { return dropped_; }
  static constexpr const char* kDroppedWhy = "a vertex not finite, or no area";

 private:
  std::vector<glm::vec3> positions_;
  std::vector<glm::vec3> normals_;
  std::vector<glm::vec2> uvs_;
  std::vector<glm::vec3> colors_;
  std::vector<Triangle> triangles_;
  std::vector<glm::vec3> faceNormals_;
  std::vector<Model> models_;
  std::vector<Sphere> spheres_;
  std::size_t dropped_ = 0;
};

}  // namespace glint
