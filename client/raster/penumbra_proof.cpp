#include "client/raster/penumbra_proof.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/geometry/region_query.h"
#include "common/math/basis.h"
#include "common/render/emitters.h"

namespace glint::gl {
namespace {

// How far a pixel's point is lifted off its surface, as a share of its
// distances to the eye and the light: past the depth buffer's rounding and
// the region query's slack. An occluder nearer the surface than this is
// missed (a contact shadow thinner than 1/1000 of the distances).
constexpr float kLift = 1e-3f;
// Where a point counts as in an emitter's plane, as a share of its distance:
// every point of the emitter sends it light at a cosine below this, not a
// visible share of a byte.
constexpr float kInPlane = 1e-4f;

// The pyramid from a lifted point to a light: its five corners (the apex
// first) and eight edges.
struct Pyramid {
  std::array<glm::vec3, 5> corners;
  static constexpr int kEdges[8][2] = {{0, 1}, {0, 2}, {0, 3}, {0, 4}, {1, 2}, {2, 3}, {3, 4}, {4, 1}};
};

// The interval of the points' projections on axis a.
template <std::size_t N>
glm::vec2 project(const std::array<glm::vec3, N>& points, const glm::vec3& a) {
  glm::vec2 range(INFINITY, -INFINITY);
  for (const glm::vec3& p : points) {
    const float d = glm::dot(p, a);
    range = {std::min(range.x, d), std::max(range.y, d)};
  }
  return range;
}

// Whether axis a (any length; none when zero) separates the pyramid from
// the interval `other` by more than `slack` times its length.
bool separates(const Pyramid& pyramid, const glm::vec3& a, glm::vec2 other, float slack) {
  const float length = glm::length(a);
  if (!(length > 0.0f)) return false;
  const glm::vec2 own = project(pyramid.corners, a);
  return own.x > other.y + slack * length || own.y < other.x - slack * length;
}

// The separating axes of a triangle and a convex polytope: the polytope's
// faces, the triangle's plane, and each pair of edges. None separating: they
// may meet.
bool triangleSeparated(const Pyramid& pyramid, const std::vector<glm::vec4>& faces,
                       const std::array<glm::vec3, 3>& t, float slack) {
  const auto separatedOn = [&](const glm::vec3& a) { return separates(pyramid, a, project(t, a), slack); };
  for (const glm::vec4& f : faces) {
    if (separatedOn(glm::vec3(f))) return true;
  }
  if (separatedOn(glm::cross(t[1] - t[0], t[2] - t[0]))) return true;
  for (int i = 0; i < 3; ++i) {
    const glm::vec3 e = t[(i + 1) % 3] - t[i];
    for (const auto& edge : Pyramid::kEdges) {
      if (separatedOn(glm::cross(e, pyramid.corners[edge[1]] - pyramid.corners[edge[0]]))) return true;
    }
  }
  return false;
}

// A sphere and a convex polytope: the direction from the centre to the
// polytope's nearest point is a face's normal, or points at an edge's nearest
// point or at a corner; one of them separates if anything does.
bool sphereSeparated(const Pyramid& pyramid, const std::vector<glm::vec4>& faces, const Sphere& s, float slack) {
  const auto separatedOn = [&](const glm::vec3& a) {
    const float c = glm::dot(s.centre, a), r = s.radius * glm::length(a);
    return separates(pyramid, a, {c - r, c + r}, slack);
  };
  for (const glm::vec4& f : faces) {
    if (separatedOn(glm::vec3(f))) return true;
  }
  for (const glm::vec3& corner : pyramid.corners) {
    if (separatedOn(corner - s.centre)) return true;
  }
  for (const auto& edge : Pyramid::kEdges) {
    const glm::vec3 a = pyramid.corners[edge[0]], d = pyramid.corners[edge[1]] - a;
    const float t = std::clamp(glm::dot(s.centre - a, d) / glm::dot(d, d), 0.0f, 1.0f);
    if (separatedOn(a + t * d - s.centre)) return true;
  }
  return false;
}

}  // namespace

bool PenumbraProof::blocks(std::uint32_t prim, const ConvexRegion& region) const {
  Pyramid pyramid;
  std::copy(region.corners.begin(), region.corners.end(), pyramid.corners.begin());
  const auto triangles = static_cast<std::uint32_t>(geometry_.triangles().size());
  if (prim >= triangles) return !sphereSeparated(pyramid, region.planes, geometry_.spheres()[prim - triangles], region.slack);
  const Triangle& t = geometry_.triangles()[prim];
  const auto& p = geometry_.positions();
  return !triangleSeparated(pyramid, region.planes, {p[t.v[0]], p[t.v[1]], p[t.v[2]]}, region.slack);
}

PenumbraProof::PenumbraProof(const Scene& scene, const EffectPlan& plan) : geometry_(scene.geometry) {
  if (!plan.softShadows) return;
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    if (!softLight(l) || !plan.lights[i]) continue;
    if (l.type == LightType::kSphere) {
      lights_.push_back({{}, l.position, glm::vec3(0.0f), l.radius});
      continue;
    }
    const glm::vec3 c = l.position - 0.5f * l.u - 0.5f * l.v;
    lights_.push_back({{c, c + l.u, c + l.u + l.v, c + l.v}, l.position, glm::normalize(glm::cross(l.u, l.v))});
  }
  if (!lights_.empty()) bvh_ = Bvh::build(scene.geometry, BvhSettings{});
}

void PenumbraProof::addEmitters(const EmitterPatches& patches) {
  for (const EmitterPatches::Patch& t : patches.patches()) {
    const glm::vec3 a = t.corner, b = a + t.edge1, c = a + t.edge2;
    // A triangle as a four-cornered base: its third edge's midpoint the
    // fourth corner (two sides of the pyramid in one plane).
    lights_.push_back({{a, b, c, 0.5f * (c + a)}, (a + b + c) / 3.0f, t.normal, 0.0f, true});
  }
  if (!lights_.empty() && bvh_.nodes().empty()) bvh_ = Bvh::build(geometry_, BvhSettings{});
}

std::optional<PenumbraProof::Base> PenumbraProof::baseFrom(const SoftLight& light, const glm::vec3& apex,
                                                           float distance) {
  if (light.radius == 0.0f) {
    // Nearly in the light's plane, the pyramid's sides are not planes.
    if (!(glm::dot(apex - light.centre, light.normal) > kLift * distance)) return std::nullopt;
    return Base{light.corners, light.normal};
  }
  // The ball, grown by the lift, is in the cone from the apex of half-angle
  // asin(r / d): it meets the plane through the centre in a circle of radius
  // r / cos, inside the square of that half-side.
  const float radius = light.radius * (1.0f + kLift);
  const glm::vec3 toApex = apex - light.centre;
  const float d = glm::length(toApex);
  const float ratio = radius / d;
  const float halfSide = radius / std::sqrt(1.0f - ratio * ratio);
  if (!std::isfinite(d) || !(ratio < 1.0f) || !std::isfinite(halfSide)) return std::nullopt;
  const glm::vec3 axis = toApex / d;
  glm::vec3 t, b;
  orthonormalBasis(axis, t, b);
  t *= halfSide;
  b *= halfSide;
  const glm::vec3& c = light.centre;
  return Base{{c - t - b, c + t - b, c + t + b, c - t + b}, axis};
}

ConvexRegion PenumbraProof::pyramidOf(const View& view) {
  ConvexRegion pyramid;
  const glm::vec3& apex = view.apex;
  const glm::vec3 inside = 0.5f * (apex + view.centre);
  pyramid.planes.push_back(planeThrough(view.centre, view.base.normal, inside));
  for (int k = 0; k < 4; ++k) {
    const glm::vec3& a = view.base.corners[k];
    const glm::vec3& b = view.base.corners[(k + 1) % 4];
    pyramid.planes.push_back(planeThrough(apex, glm::cross(a - apex, b - apex), inside));
  }
  pyramid.corners = {apex, view.base.corners[0], view.base.corners[1], view.base.corners[2], view.base.corners[3]};
  finishRegion(pyramid);
  return pyramid;
}

bool PenumbraProof::clear(const View& view, std::optional<std::span<const std::uint32_t>> suspects) const {
  const ConvexRegion pyramid = pyramidOf(view);
  if (!suspects) {
    for (std::uint32_t prim : primitivesInRegion(bvh_, geometry_, pyramid, UINT32_MAX)) {
      if (blocks(prim, pyramid)) return false;
    }
    return true;
  }
  for (std::uint32_t prim : *suspects) {
    if (primitiveInRegion(geometry_, prim, pyramid) && blocks(prim, pyramid)) return false;
  }
  return true;
}

PenumbraProof::View PenumbraProof::viewOf(SoftLight light, const glm::vec3& p, const glm::vec3& eye) {
  const glm::vec3 toLight = light.centre - p;
  const float distance = glm::length(toLight);
  const float side = glm::dot(p - light.centre, light.normal);
  // An emitter lights the side p is on; a point in its plane (a ceiling
  // around a lamp set in it) gets next to nothing from it.
  if (light.emitter && std::abs(side) <= kInPlane * distance) return {};
  if (light.emitter && side < 0.0f) light.normal = -light.normal;
  // Behind an area light: no light, nothing to prove.
  if (light.radius == 0.0f && !light.emitter && side <= 0.0f) return {};
  View view;
  view.apex = p + (kLift * (distance + glm::length(p - eye)) / distance) * toLight;
  const std::optional<Base> base = baseFrom(light, view.apex, distance);
  if (!base) {
    view.kind = View::Kind::kUnprovable;
    return view;
  }
  view.kind = View::Kind::kPyramid;
  view.base = *base;
  view.centre = light.centre;
  if (light.emitter) {
    const float keep = 1.0f - Emitters::kShortOfEmitter;
    for (glm::vec3& corner : view.base.corners) corner = view.apex + keep * (corner - view.apex);
    view.centre = view.apex + keep * (view.centre - view.apex);
  }
  return view;
}

bool PenumbraProof::seesWhole(const glm::vec3& p, const glm::vec3& eye) const {
  return seesWholeAsking(p, eye, std::nullopt);
}

bool PenumbraProof::seesWhole(const glm::vec3& p, const glm::vec3& eye,
                              std::span<const std::uint32_t> suspects) const {
  return seesWholeAsking(p, eye, suspects);
}

bool PenumbraProof::seesWholeAsking(const glm::vec3& p, const glm::vec3& eye,
                                    std::optional<std::span<const std::uint32_t>> suspects) const {
  for (const SoftLight& light : lights_) {
    const View view = viewOf(light, p, eye);
    if (view.kind == View::Kind::kUnprovable) return false;
    if (view.kind == View::Kind::kPyramid && !clear(view, suspects)) return false;
  }
  return true;
}

bool PenumbraProof::plainlyBlocked(const glm::vec3& p, const glm::vec3& eye) const {
  for (const SoftLight& light : lights_) {
    const View view = viewOf(light, p, eye);
    if (view.kind != View::Kind::kPyramid) continue;
    const glm::vec3 toCentre = view.centre - view.apex;
    const float length = glm::length(toCentre);
    if (length > 0.0f && bvh_.occluded(Ray(view.apex, toCentre / length), length)) return true;
  }
  return false;
}

namespace {

// The plane of outward unit normal n that has every point on its inner
// side, the farthest on it.
glm::vec4 planeAround(const glm::vec3& n, const std::vector<glm::vec3>& points) {
  float d = -INFINITY;
  for (const glm::vec3& p : points) d = std::max(d, glm::dot(n, p));
  return {n, d};
}

}  // namespace

// Points whose hull holds every pyramid of a block. A sphere light's base
// turns with the apex: every pyramid's corners. An area light's base is the
// same from every apex, and an emitter's is drawn towards its apex by
// `keep`, which is affine in the apex: with the apexes in their box, the
// bases' corners lie in the boxes those corners have from the box's eight
// corners, whatever the block's size.
std::vector<glm::vec3> PenumbraProof::cornersAround(const SoftLight& light, const std::vector<View>& views) {
  std::vector<glm::vec3> corners;
  if (light.radius > 0.0f) {
    for (const View& v : views) {
      corners.push_back(v.apex);
      corners.insert(corners.end(), v.base.corners.begin(), v.base.corners.end());
    }
    return corners;
  }
  Bounds3 apexes;
  for (const View& v : views) apexes.expand(v.apex);
  const float keep = light.emitter ? 1.0f - Emitters::kShortOfEmitter : 1.0f;
  for (const glm::vec3& b : apexes.corners()) {
    corners.push_back(b);
    for (const glm::vec3& c : light.corners) corners.push_back(light.emitter ? b + keep * (c - b) : c);
  }
  return corners;
}

// A region around every pyramid of a block of points: the planes of the
// middle one's faces and of the box, each moved out to take in the points
// that hold every pyramid (a pyramid is their hull), the corners those.
ConvexRegion PenumbraProof::regionAround(const SoftLight& light, const std::vector<View>& views) {
  ConvexRegion region;
  region.corners = cornersAround(light, views);
  const View& middle = views[views.size() / 2];
  const glm::vec3 inside = 0.5f * (middle.apex + middle.centre);
  region.planes.push_back(planeAround(-middle.base.normal, region.corners));
  for (int k = 0; k < 4; ++k) {
    const glm::vec3& a = middle.base.corners[k];
    const glm::vec3& b = middle.base.corners[(k + 1) % 4];
    const glm::vec4 side = planeThrough(middle.apex, glm::cross(a - middle.apex, b - middle.apex), inside);
    region.planes.push_back(planeAround(glm::vec3(side), region.corners));
  }
  for (int axis = 0; axis < 3; ++axis) {
    glm::vec3 n(0.0f);
    n[axis] = 1.0f;
    region.planes.push_back(planeAround(n, region.corners));
    region.planes.push_back(planeAround(-n, region.corners));
  }
  finishRegion(region);
  return region;
}

std::optional<std::vector<PenumbraProof::View>> PenumbraProof::viewsOf(const SoftLight& light,
                                                                       std::span<const glm::vec3> points,
                                                                       const glm::vec3& eye) const {
  std::vector<View> views;
  for (const glm::vec3& p : points) {
    const View view = viewOf(light, p, eye);
    if (view.kind == View::Kind::kUnprovable) return std::nullopt;
    if (view.kind == View::Kind::kPyramid) views.push_back(view);
  }
  return views;
}

bool PenumbraProof::allSeeWhole(std::span<const glm::vec3> points, const glm::vec3& eye) const {
  for (const SoftLight& light : lights_) {
    const std::optional<std::vector<View>> views = viewsOf(light, points, eye);
    if (!views) return false;
    if (views->empty()) continue;
    if (!primitivesInRegion(bvh_, geometry_, regionAround(light, *views), UINT32_MAX).empty()) return false;
  }
  return true;
}

std::optional<std::vector<std::uint32_t>> PenumbraProof::suspects(std::span<const glm::vec3> points,
                                                                  const glm::vec3& eye) const {
  std::vector<std::uint32_t> all;
  for (const SoftLight& light : lights_) {
    const std::optional<std::vector<View>> views = viewsOf(light, points, eye);
    if (!views) return std::nullopt;
    if (views->empty()) continue;
    for (std::uint32_t prim : primitivesInRegion(bvh_, geometry_, regionAround(light, *views), UINT32_MAX)) {
      if (std::find(all.begin(), all.end(), prim) == all.end()) all.push_back(prim);
    }
  }
  return all;
}

}  // namespace glint::gl
