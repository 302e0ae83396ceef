#include "common/render/tracer.h"

#include <glm/geometric.hpp>

#include "common/math/float_bits.h"
#include "common/render/optics.h"
#include "common/render/shading.h"

namespace glint {

Tracer::Tracer(const Scene& scene, const Bvh& bvh, const TracingSettings& tracing, const EffectPlan& plan)
    : scene_(scene), bvh_(bvh), tracing_(tracing), plan_(plan) {}

glm::vec3 Tracer::radiance(const Ray& ray, RayStats& stats) const {
  ++stats.primary;
  return trace(ray, 1, 1.0f, false, stats);
}

glm::vec3 Tracer::lightIntensity(int light, float distance) const {
  const PointLight& l = scene_.lights[light];
  if (!plan_.attenuation) return l.color / l.attenuation.x;  // constant: no distance term
  return attenuate(l.color, l.attenuation, distance);
}

glm::vec3 Tracer::emitted(const Material& m, const glm::vec2& uv) const {
  return m.emissionTexture >= 0 ? m.emission * scene_.textures[m.emissionTexture].evaluate(uv) : m.emission;
}

glm::vec3 Tracer::shade(const SurfaceHit& s, const glm::vec3& outside, const glm::vec3& toViewer,
                        const Material& m, const MaterialEffects& e, RayStats& stats) const {
  // The colour times the texture (glTF's baseColorFactor x baseColorTexture;
  // a textured material's colour is 1 unless given, and 1 x t is t exactly).
  // A mesh's vertex colours multiply both (glTF's COLOR_0).
  const glm::vec3 base =
      e.textured && m.texture >= 0 ? m.color * scene_.textures[m.texture].evaluate(s.uv) : m.color;
  const glm::vec3 c = plan_.vertexColors ? base * s.color : base;
  glm::vec3 result = phongAmbient(c, m.ambient);
  if (e.emits) result += emitted(m, s.uv);
  if (!e.direct) return result;
  for (int i = 0; i < static_cast<int>(scene_.lights.size()); ++i) {
    if (!plan_.lights[i]) continue;
    const glm::vec3 toLight = scene_.lights[i].position - s.p;
    const float distance = glm::length(toLight);
    if (!(distance > 0.0f)) continue;
    const glm::vec3 l = toLight / distance;
    // A light behind the geometric surface or the shading normal adds nothing.
    if (glm::dot(l, s.ng) <= 0.0f || glm::dot(l, s.ns) <= 0.0f) continue;
    if (plan_.shadows) {
      ++stats.shadow;
      const glm::vec3 fromOrigin = scene_.lights[i].position - outside;
      const float shadowDistance = glm::length(fromOrigin);
      if (bvh_.occluded(Ray(outside, fromOrigin / shadowDistance), shadowDistance)) {
        ++stats.shadowBlocked;
        continue;
      }
    }
    const glm::vec3 lightI = lightIntensity(i, distance);
    result += phongDiffuse(lightI, c, m.diffuse, s.ns, l);
    if (e.specular) result += phongSpecular(lightI, m.specular, m.shininess, s.ns, l, toViewer);
  }
  return result;
}

glm::vec3 Tracer::trace(const Ray& ray, int depth, float weight, bool inside,
                        RayStats& stats) const {
  const std::optional<Hit> hit = bvh_.intersect(ray, kInfinity);
  if (!hit) return scene_.background;
  const std::uint32_t material = scene_.geometry.materialOf(hit->prim);
  const Material& m = scene_.materials[material];
  const MaterialEffects& e = plan_.materials[material];
  const SurfaceHit s = scene_.geometry.surface(ray, *hit, e.textured, plan_.vertexColors);
  const glm::vec3 outside = offsetRayOrigin(s.p, s.error, s.ng);
  glm::vec3 color = shade(s, outside, -ray.d, m, e, stats);
  if (depth >= tracing_.maxDepth || !(e.reflects || e.refracts)) return color;

  float kr = m.reflectivity;
  float kt = 0.0f;
  glm::vec3 refracted{0.0f};
  if (m.transparency > 0.0f) {
    // Entering: air -> material; leaving: material -> air.
    const float eta = inside ? m.ior : 1.0f / m.ior;
    std::optional<glm::vec3> t = refract(ray.d, s.ns, eta);
    if (t && glm::dot(*t, s.ng) >= 0.0f) t = refract(ray.d, s.ng, eta);
    if (t) {
      kt = m.transparency;
      refracted = *t;
    } else {
      kr += m.transparency;  // total internal reflection
    }
  }
  const float minWeight = tracing_.minWeight;
  if (e.reflects && kr > 0.0f && weight * kr >= minWeight) {
    ++stats.reflection;
    color += kr * trace(Ray(outside, mirrorDirection(ray.d, s.ns, s.ng)), depth + 1, weight * kr, inside, stats);
  }
  if (e.refracts && kt > 0.0f && weight * kt >= minWeight) {
    ++stats.refraction;
    color += kt * trace(Ray(offsetRayOrigin(s.p, s.error, -s.ng), refracted), depth + 1, weight * kt, !inside,
                        stats);
  }
  return color;
}

}  // namespace glint
