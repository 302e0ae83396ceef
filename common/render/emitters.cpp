#include "common/render/emitters.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/math/circular.h"
#include "common/math/float_bits.h"
#include "common/render/surface_terms.h"

namespace glint {
namespace {

constexpr float kPi = 3.14159265358979f;

float areaOf(const Geometry& g, std::uint32_t prim) {
  if (g.isSphere(prim)) {
    const float r = g.spheres()[prim - g.triangles().size()].radius;
    return 4.0f * kPi * r * r;
  }
  const Triangle& t = g.triangles()[prim];
  const auto& p = g.positions();
  return 0.5f * glm::length(glm::cross(p[t.v[1]] - p[t.v[0]], p[t.v[2]] - p[t.v[0]]));
}

}  // namespace

Emitters::Emitters(const Geometry& geometry, const EffectPlan& plan) : geometry_(geometry) {
  if (!plan.emission) return;
  for (std::uint32_t prim = 0; prim < geometry.primitiveCount(); ++prim) {
    if (!plan.materials[geometry.materialOf(prim)].emits) continue;
    const float a = areaOf(geometry, prim);
    if (!(a > 0.0f) || !std::isfinite(a)) continue;
    total_ += a;
    prims_.push_back(prim);
    cumulative_.push_back(total_);
  }
}

Emitters::Point Emitters::sample(const glm::vec2& pickAndPlace) const {
  const float target = pickAndPlace.x * total_;
  const auto at = std::upper_bound(cumulative_.begin(), cumulative_.end(), target);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(at - cumulative_.begin()), prims_.size() - 1);
  const std::uint32_t prim = prims_[i];
  const float before = i == 0 ? 0.0f : cumulative_[i - 1];
  const float share = cumulative_[i] - before;
  const glm::vec2 u{share > 0.0f ? std::clamp((target - before) / share, 0.0f, kOneMinusEpsilon) : 0.5f,
                    pickAndPlace.y};
  if (geometry_.isSphere(prim)) {
    const Sphere& s = geometry_.spheres()[prim - geometry_.triangles().size()];
    const float z = 1.0f - 2.0f * u.x;  // uniform over the sphere
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const SineCosine phi = turn(u.y);
    const glm::vec3 n(r * phi.cos, r * phi.sin, z);
    return {s.centre + s.radius * n, n, prim, 0.0f, 0.0f};
  }
  // Uniform over the triangle: b0 = 1 - sqrt(u.x), b1 = u.y sqrt(u.x).
  const float su = std::sqrt(u.x);
  const float b1 = u.y * su, b2 = su - b1;
  const Triangle& t = geometry_.triangles()[prim];
  const auto& p = geometry_.positions();
  const glm::vec3 q = (1.0f - b1 - b2) * p[t.v[0]] + b1 * p[t.v[1]] + b2 * p[t.v[2]];
  return {q, geometry_.faceNormals()[prim], prim, b1, b2};
}

std::optional<Emitters::Seen> Emitters::seenFrom(const Scene& scene, const EffectPlan& plan, const glm::vec3& p,
                                                 const glm::vec2& pickAndPlace) const {
  const Point e = sample(pickAndPlace);
  const glm::vec3 to = e.p - p;
  const float d = glm::length(to);
  if (!(d > 0.0f)) return std::nullopt;
  const glm::vec3 wi = to / d;
  const float cosE = std::abs(glm::dot(e.n, wi));
  if (!(cosE > 0.0f)) return std::nullopt;
  const std::uint32_t material = geometry_.materialOf(e.prim);
  glm::vec2 uv(0.0f);
  if (plan.materials[material].textured) {
    const Ray toward(p, wi);
    uv = geometry_.surface(toward, Hit{d, e.prim, 1.0f - e.b1 - e.b2, e.b1, e.b2}, true, false).uv;
  }
  const glm::vec3 radiance = surfaceEmission(scene, scene.materials[material], uv);
  return Seen{wi, d * (1.0f - kShortOfEmitter), radiance, d * d / (cosE * total_)};
}

}  // namespace glint
