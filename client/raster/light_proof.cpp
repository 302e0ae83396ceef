#include "client/raster/light_proof.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "common/base/compute_pool.h"
#include "common/geometry/bvh.h"
#include "common/geometry/region_query.h"

namespace glint::gl {
namespace {

// The tetrahedron between `light` and the triangle; empty when the light
// lies (nearly) in the triangle's plane. The triangle's corners are shared:
// its neighbours touch the tetrahedron there without entering it; its plane
// is the open base.
std::optional<ConvexRegion> tetrahedron(const glm::vec3& light, const std::array<glm::vec3, 3>& v) {
  const glm::vec3 normal = glm::cross(v[1] - v[0], v[2] - v[0]);
  const float height = std::abs(glm::dot(glm::normalize(normal), light - v[0]));
  const float size =
      glm::length(light - v[0]) + glm::length(v[1] - v[0]) + glm::length(v[2] - v[0]);
  if (!(height > size * 1e-3f)) return std::nullopt;
  ConvexRegion region;
  region.planes.push_back(planeThrough(v[0], normal, light));
  region.openBase = true;
  for (std::size_t i = 0; i < 3; ++i) {
    const glm::vec3& p = v[i];
    const glm::vec3& q = v[(i + 1) % 3];
    region.planes.push_back(planeThrough(light, glm::cross(p - light, q - light), v[(i + 2) % 3]));
  }
  region.corners = {light, v[0], v[1], v[2]};
  region.shared = {v[0], v[1], v[2]};
  finishRegion(region);
  return region;
}

// A square pyramid from `light` that holds every segment from the light to
// the sphere's lit side, cut by the plane through the centre; empty when the
// light is (nearly) inside the sphere.
std::optional<ConvexRegion> pyramid(const glm::vec3& light, const Sphere& sphere) {
  const glm::vec3 toCentre = sphere.centre - light;
  const float distance = glm::length(toCentre);
  const float radius = sphere.radius * 1.001f;
  if (!(distance > radius * 1.01f)) return std::nullopt;
  const glm::vec3 axis = toCentre / distance;
  const float sine = radius / distance, cosine = std::sqrt(1.0f - sine * sine);
  const glm::vec3 u =
      glm::normalize(std::abs(axis.x) < 0.9f ? glm::cross(axis, glm::vec3(1, 0, 0))
                                             : glm::cross(axis, glm::vec3(0, 1, 0)));
  const glm::vec3 w = glm::cross(axis, u);
  ConvexRegion region;
  region.planes.push_back({axis, glm::dot(axis, sphere.centre)});
  const float half = distance * sine / cosine;
  region.corners.push_back(light);
  for (const glm::vec3& side : {u, -u, w, -w}) {
    const glm::vec3 n = side * cosine - axis * sine;
    region.planes.push_back({n, glm::dot(n, light)});
  }
  for (float a : {-1.0f, 1.0f}) {
    for (float b : {-1.0f, 1.0f}) region.corners.push_back(sphere.centre + half * (a * u + b * w));
  }
  finishRegion(region);
  return region;
}

// A rectangle in a triangle's plane, in coordinates along two unit axes of
// the plane from its first vertex; a side may be infinite.
struct PlaneRect {
  glm::vec3 origin, u, v;
  glm::vec2 min{INFINITY}, max{-INFINITY};

  glm::vec2 at(const glm::vec3& p) const {
    return {glm::dot(p - origin, u), glm::dot(p - origin, v)};
  }
  void expand(const glm::vec3& p) {
    min = glm::min(min, at(p));
    max = glm::max(max, at(p));
  }
  // Open towards direction d: every side d points to (or nearly along) is
  // infinite.
  void extendTowards(const glm::vec3& d) {
    const glm::vec2 along(glm::dot(d, u), glm::dot(d, v));
    const float tiny = 1e-5f * glm::length(d);
    for (int axis = 0; axis < 2; ++axis) {
      if (along[axis] < tiny) min[axis] = -INFINITY;
      if (along[axis] > -tiny) max[axis] = INFINITY;
    }
  }
  glm::vec3 corner(int i) const {
    return origin + (i & 1 ? max.x : min.x) * u + (i & 2 ? max.y : min.y) * v;
  }
};

// A primitive as a convex polytope: its corners and edges (a sphere's by
// its bounding box).
struct Caster {
  std::vector<glm::vec3> corners;
  std::vector<std::pair<int, int>> edges;
};

Caster casterOf(const Geometry& g, std::uint32_t prim) {
  Caster c;
  if (g.isSphere(prim)) {
    const std::array<glm::vec3, 8> box = g.primitiveBounds(prim).corners();
    c.corners.assign(box.begin(), box.end());
    for (int i = 0; i < 8; ++i) {
      for (int bit : {1, 2, 4}) {
        if (!(i & bit)) c.edges.emplace_back(i, i | bit);
      }
    }
    return c;
  }
  const Triangle& t = g.triangles()[prim];
  c.corners = {g.positions()[t.v[0]], g.positions()[t.v[1]], g.positions()[t.v[2]]};
  c.edges = {{0, 1}, {1, 2}, {2, 0}};
  return c;
}

// Grows `shadow` (in the plane, whose normal points to the light) by the
// caster's shadow, projected from the light. The part of the caster below
// the cut (just under the light's height) projects to points. The part
// above casts its shadow at least 10^4 times its distance from the light's
// vertical (at the light's foot) away from that foot: beyond `reach` (how
// far the receiver extends from the foot) it misses the receiver, else it
// opens the rectangle towards each of its corners' directions from the
// light and adds the foot.
void castShadow(const Caster& caster, const glm::vec3& light, const glm::vec4& plane, float reach,
                PlaneRect& shadow) {
  const glm::vec3 n(plane);
  const float lightHeight = glm::dot(n, light) - plane.w;
  const float cut = lightHeight * 0.9999f;
  const glm::vec3 foot = light - n * lightHeight;
  const auto height = [&](const glm::vec3& p) { return glm::dot(n, p) - plane.w; };
  const auto project = [&](const glm::vec3& p) {
    shadow.expand(light + (p - light) * (lightHeight / (lightHeight - height(p))));
  };
  std::vector<glm::vec3> upper;  // the corners of the part above the cut
  for (const glm::vec3& p : caster.corners) {
    if (height(p) < cut)
      project(p);
    else
      upper.push_back(p);
  }
  if (upper.empty()) return;
  for (const auto& [i, j] : caster.edges) {
    const glm::vec3 a = caster.corners[static_cast<std::size_t>(i)],
                    b = caster.corners[static_cast<std::size_t>(j)];
    const float ha = height(a), hb = height(b);
    if ((ha < cut) == (hb < cut)) continue;
    upper.push_back(a + (b - a) * ((cut - ha) / (hb - ha)));
    project(upper.back());
  }
  PlaneRect box = shadow;  // the upper part's extent along the plane
  box.min = glm::vec2(INFINITY);
  box.max = glm::vec2(-INFINITY);
  for (const glm::vec3& p : upper) box.expand(p);
  const glm::vec2 f = box.at(foot);
  if (glm::length(glm::max(glm::max(box.min - f, f - box.max), glm::vec2(0.0f))) * 1e4f >
      reach * 1.01f)
    return;
  shadow.expand(foot);
  for (const glm::vec3& p : upper) shadow.extendTowards(p - light);
}

// The spot of `light` on triangle `prim`, whose tetrahedron the primitives
// `inside` may enter: their shadow on the triangle's plane, clipped to the
// triangle's own rectangle. Empty (no corners) when that shadow misses the
// triangle; the whole triangle, with no plane, when `whole` (the light lies
// in the triangle's plane).
ShadowSpot triangleSpot(const Geometry& g, std::uint32_t prim, const glm::vec3& light,
                        const std::vector<std::uint32_t>& inside, float slack, bool whole) {
  const Triangle& t = g.triangles()[prim];
  const std::array<glm::vec3, 3> v{g.positions()[t.v[0]], g.positions()[t.v[1]],
                                   g.positions()[t.v[2]]};
  ShadowSpot spot;
  spot.prim = prim;
  const glm::vec4 plane =
      planeThrough(v[0], glm::cross(v[1] - v[0], v[2] - v[0]), v[0] - (light - v[0]));
  PlaneRect own{v[0], glm::normalize(v[1] - v[0]), {}, {}, {}};
  own.v = glm::cross(glm::vec3(plane), own.u);
  for (const glm::vec3& p : v) own.expand(p);
  PlaneRect shadow = own;
  if (!whole) {
    spot.plane = plane;  // normal towards the light
    shadow.min = glm::vec2(INFINITY);
    shadow.max = glm::vec2(-INFINITY);
    const glm::vec2 foot =
        own.at(light - glm::vec3(plane) * (glm::dot(glm::vec3(plane), light) - plane.w));
    float reach = 0.0f;
    for (int i = 0; i < 4; ++i) reach = std::max(reach, glm::length(own.at(own.corner(i)) - foot));
    for (std::uint32_t other : inside) castShadow(casterOf(g, other), light, plane, reach, shadow);
    shadow.min = glm::max(shadow.min - slack, own.min);
    shadow.max = glm::min(shadow.max + slack, own.max);
    if (shadow.min.x > shadow.max.x || shadow.min.y > shadow.max.y) return spot;
  }
  for (int i = 0; i < 4; ++i) spot.corners[static_cast<std::size_t>(i)] = shadow.corner(i);
  spot.cornerCount = 4;
  return spot;
}

// The spot of the light at `light` on primitive `prim`; none when the light
// provably reaches all of it.
std::optional<ShadowSpot> spotOf(const Geometry& g, const Bvh& bvh, std::uint32_t prim,
                                 const glm::vec3& light) {
  if (g.isSphere(prim)) {
    const Sphere& sphere = g.spheres()[prim - g.triangles().size()];
    const auto region = pyramid(light, sphere);
    if (region && primitivesInRegion(bvh, g, *region, prim).empty()) return std::nullopt;
    ShadowSpot spot;
    spot.prim = prim;
    spot.corners = sphere.bounds().corners();
    spot.cornerCount = 8;
    return spot;
  }
  const Triangle& t = g.triangles()[prim];
  const auto region =
      tetrahedron(light, {g.positions()[t.v[0]], g.positions()[t.v[1]], g.positions()[t.v[2]]});
  const auto inside =
      region ? primitivesInRegion(bvh, g, *region, prim) : std::vector<std::uint32_t>{};
  if (region && inside.empty()) return std::nullopt;
  const ShadowSpot spot =
      triangleSpot(g, prim, light, inside, region ? region->slack : 0.0f, !region);
  if (spot.cornerCount == 0) return std::nullopt;
  return spot;
}

// All of primitive `prim` as a spot: a directional light's (no proof is
// attempted for parallel light).
std::optional<ShadowSpot> wholeSpot(const Geometry& g, std::uint32_t prim) {
  if (!g.isSphere(prim)) {
    const Triangle& t = g.triangles()[prim];
    const glm::vec3 v0 = g.positions()[t.v[0]];
    const glm::vec3 normal = glm::cross(g.positions()[t.v[1]] - v0, g.positions()[t.v[2]] - v0);
    return triangleSpot(g, prim, v0 + normal, {}, 0.0f, true);
  }
  ShadowSpot spot;
  spot.prim = prim;
  spot.corners = g.spheres()[prim - g.triangles().size()].bounds().corners();
  spot.cornerCount = 8;
  return spot;
}

}  // namespace

LightProof LightProof::prove(const Scene& scene, const std::vector<bool>& casts) {
  const Geometry& g = scene.geometry;
  const Bvh bvh = Bvh::build(g, BvhSettings{});
  // Each primitive's proof stands alone: the primitives are cut into one
  // run per thread of the compute pool, and the runs' spots joined in order.
  const std::uint32_t count = g.primitiveCount();
  const std::uint32_t runs =
      std::clamp(static_cast<std::uint32_t>(computePool().size()), 1u, std::max(1u, count / 64));
  std::vector<std::vector<ShadowSpot>> found(runs);
  computePool().parallelFor(runs, [&](std::size_t r) {
    for (std::size_t light = 0; light < scene.lights.size(); ++light) {
      if (!casts[light]) continue;
      const Light& l = scene.lights[light];
      for (std::uint32_t prim = count * r / runs; prim < count * (r + 1) / runs; ++prim) {
        if (auto spot = l.type == LightType::kDirectional ? wholeSpot(g, prim) : spotOf(g, bvh, prim, l.position)) {
          spot->light = static_cast<int>(light);
          found[r].push_back(*spot);
        }
      }
    }
  });
  LightProof proof;
  for (const std::vector<ShadowSpot>& spots : found) proof.spots.insert(proof.spots.end(), spots.begin(), spots.end());
  std::stable_sort(proof.spots.begin(), proof.spots.end(),
                   [](const ShadowSpot& a, const ShadowSpot& b) { return a.light < b.light; });
  return proof;
}

}  // namespace glint::gl
