#include "common/geometry/geometry.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/base/heap_tuning.h"
#include "common/math/finite.h"
#include "common/math/float_bits.h"

namespace glint {
namespace {

glm::vec3 faceForward(const glm::vec3& n, const glm::vec3& d) {
  return glm::dot(n, d) > 0.0f ? -n : n;
}

// Appends a mesh's vertex attribute (or n zero values where it has none) to
// the scene's: the mesh's storage is taken where the scene's is empty, and
// the room it grows into is faulted in at once (heap_tuning.h).
template <typename T>
void appendAttribute(std::vector<T>& to, std::vector<T>& from, std::size_t n) {
  if (to.empty() && !from.empty()) {
    to.swap(from);
    return;
  }
  reservePrefaulted(to, to.size() + n);
  if (from.empty()) {
    to.resize(to.size() + n, T(0.0f));
  } else {
    to.insert(to.end(), from.begin(), from.end());
  }
}

// Appends a mesh's vertex colours: nothing while no mesh has them; white
// for the vertices before the first mesh that has, and for a mesh without.
void appendColors(std::vector<glm::vec3>& to, std::vector<glm::vec3>& from, std::size_t before, std::size_t n) {
  if (from.empty() && to.empty()) return;
  if (to.empty()) to.assign(before, glm::vec3(1.0f));
  if (from.empty()) {
    to.resize(to.size() + n, glm::vec3(1.0f));
  } else {
    to.insert(to.end(), from.begin(), from.end());
  }
}

}  // namespace

void Geometry::addMesh(MeshInput mesh) {
  // No normals: zero vectors, which shading replaces by the geometric normal
  // (flat facets, as in OpenGL without per-vertex normals).
  const std::size_t n = mesh.positions.size();
  const auto base = static_cast<std::uint32_t>(positions_.size());
  const auto model = static_cast<std::uint32_t>(models_.size());
  models_.push_back({mesh.material});
  appendAttribute(positions_, mesh.positions, n);
  appendAttribute(normals_, mesh.normals, n);
  appendAttribute(uvs_, mesh.uvs, n);
  appendColors(colors_, mesh.colors, base, n);
  reservePrefaulted(triangles_, triangles_.size() + mesh.indices.size() / 3);
  reservePrefaulted(faceNormals_, faceNormals_.size() + mesh.indices.size() / 3);
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    std::array<std::uint32_t, 3> v = {mesh.indices[i] + base, mesh.indices[i + 1] + base, mesh.indices[i + 2] + base};
    std::sort(v.begin(), v.end());
    const glm::vec3& a = positions_[v[0]];
    const glm::vec3& b = positions_[v[1]];
    const glm::vec3& c = positions_[v[2]];
    const glm::vec3 nf = glm::cross(b - a, c - a);
    if (!allFinite(a) || !allFinite(b) || !allFinite(c) || !allFinite(nf) || glm::dot(nf, nf) == 0.0f) {
      ++dropped_;
      continue;
    }
    triangles_.push_back({v, model});
    faceNormals_.push_back(glm::normalize(nf));
  }
}

Bounds3 Geometry::primitiveBounds(std::uint32_t prim) const {
  if (isSphere(prim)) return spheres_[prim - triangles_.size()].bounds();
  Bounds3 b;
  for (std::uint32_t v : triangles_[prim].v) b.expand(positions_[v]);
  return b;
}

Bounds3 Geometry::bounds() const {
  Bounds3 b;
  for (const Triangle& t : triangles_) {
    for (std::uint32_t v : t.v) b.expand(positions_[v]);
  }
  for (const Sphere& s : spheres_) b.expand(s.bounds());
  return b;
}

std::uint32_t Geometry::materialOf(std::uint32_t prim) const {
  if (isSphere(prim)) return spheres_[prim - triangles_.size()].material;
  return models_[triangles_[prim].model].material;
}

std::optional<Hit> Geometry::intersect(std::uint32_t prim, const Ray& ray, const WatertightRay& w, float tMax) const {
  if (isSphere(prim)) {
    const std::optional<float> t = intersectSphere(spheres_[prim - triangles_.size()], ray, tMax);
    if (!t) return std::nullopt;
    return Hit{*t, prim, 0.0f, 0.0f, 0.0f};
  }
  const Triangle& tri = triangles_[prim];
  const std::optional<TriangleHit> h =
      intersectTriangle(ray, w, positions_[tri.v[0]], positions_[tri.v[1]], positions_[tri.v[2]], tMax);
  if (!h) return std::nullopt;
  return Hit{h->t, prim, h->b0, h->b1, h->b2};
}

SurfaceHit Geometry::surface(const Ray& ray, const Hit& hit, bool withUv, bool withColor) const {
  SurfaceHit s;
  s.uv = glm::vec2(0.0f);
  s.color = glm::vec3(1.0f);
  if (isSphere(hit.prim)) {
    const Sphere& sphere = spheres_[hit.prim - triangles_.size()];
    s.p = projectToSphere(sphere, ray.o + hit.t * ray.d);
    // Projection leaves p off the surface by a few ulps of the radius and of
    // the centre's coordinates (pbrt-v4 6.8.5 bounds the object-space part by gamma(5)).
    const glm::vec3 c = glm::abs(sphere.centre);
    s.error = gamma(6) * (std::max({c.x, c.y, c.z}) + sphere.radius);
    const glm::vec3 n = (s.p - sphere.centre) / sphere.radius;
    s.ng = faceForward(n, ray.d);
    s.ns = s.ng;
    if (withUv) {
      // u: longitude / 360, v: latitude from the south pole / 180 (y is up).
      const float u = std::atan2(n.x, n.z) / (2.0f * 3.14159265f);
      const float v = std::acos(std::clamp(-n.y, -1.0f, 1.0f)) / 3.14159265f;
      s.uv = {u < 0.0f ? u + 1.0f : u, v};
    }
    return s;
  }
  const Triangle& tri = triangles_[hit.prim];
  const glm::vec3& a = positions_[tri.v[0]];
  const glm::vec3& b = positions_[tri.v[1]];
  const glm::vec3& c = positions_[tri.v[2]];
  // Barycentric reconstruction is exact to a few ulps of the vertices
  // (Wächter and Binder, Ray Tracing Gems chapter 6).
  s.p = hit.b0 * a + hit.b1 * b + hit.b2 * c;
  // pbrt-v4 6.8.5: the interpolation error is at most gamma(7) sum |b_i p_i|.
  const glm::vec3 absSum = glm::abs(hit.b0 * a) + glm::abs(hit.b1 * b) + glm::abs(hit.b2 * c);
  s.error = gamma(7) * std::max({absSum.x, absSum.y, absSum.z});
  s.ng = faceForward(faceNormals_[hit.prim], ray.d);
  const glm::vec3 n = hit.b0 * normals_[tri.v[0]] + hit.b1 * normals_[tri.v[1]] + hit.b2 * normals_[tri.v[2]];
  const float len = glm::length(n);
  s.ns = len > 0.0f && std::isfinite(len) ? n / len : s.ng;
  if (glm::dot(s.ns, s.ng) < 0.0f) s.ns = -s.ns;
  if (withUv) s.uv = hit.b0 * uvs_[tri.v[0]] + hit.b1 * uvs_[tri.v[1]] + hit.b2 * uvs_[tri.v[2]];
  if (withColor && !colors_.empty()) {
    s.color = hit.b0 * colors_[tri.v[0]] + hit.b1 * colors_[tri.v[1]] + hit.b2 * colors_[tri.v[2]];
  }
  return s;
}

Geometry::LiftedPoint Geometry::lifted(const Hit& hit, const SurfaceHit& s) const {
  if (isSphere(hit.prim)) return {s.p, s.error};
  const Triangle& tri = triangles_[hit.prim];
  const std::array<float, 3> b = {hit.b0, hit.b1, hit.b2};
  const glm::vec3 n = b[0] * normals_[tri.v[0]] + b[1] * normals_[tri.v[1]] + b[2] * normals_[tri.v[2]];
  const float side = glm::dot(n, s.ns) < 0.0f ? -1.0f : 1.0f;
  glm::vec3 lift(0.0f);
  for (std::size_t i = 0; i < 3; ++i) {
    const glm::vec3& corner = normals_[tri.v[i]];
    const float len = glm::length(corner);
    if (!(len > 0.0f)) continue;
    const glm::vec3 ni = (side / len) * corner;
    const float below = glm::dot(s.p - positions_[tri.v[i]], ni);
    if (below < 0.0f) lift -= b[i] * below * ni;
  }
  // Lifting can only move the point off the triangle's outer side.
  if (!allFinite(lift) || !(glm::dot(lift, s.ng) > 0.0f)) return {s.p, s.error};
  const glm::vec3 p = s.p + lift;
  // The sum rounds each coordinate by half an ulp of its magnitude.
  const glm::vec3 m = glm::abs(p);
  return {p, s.error + gamma(2) * std::max({m.x, m.y, m.z})};
}

}  // namespace glint
