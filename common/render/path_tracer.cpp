#include "common/render/path_tracer.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/geometry/sphere.h"
#include "common/math/finite.h"
#include "common/math/float_bits.h"
#include "common/render/optics.h"
#include "common/scene/shading.h"
#include "common/render/sphere_light.h"
#include "common/render/surface_terms.h"

namespace glint {
namespace {

constexpr float kPi = 3.14159265358979f;
// The pairs of sample dimensions a bounce draws (SampleKey::stratified),
// from its first: the direction; the lobe and the roulette; the point on the
// emitters; the environment's direction; then one a light.
constexpr int kDirectionPair = 0, kLobePair = 1, kEmitterPair = 2, kSkyPair = 3, kFirstLightPair = 4;

float powerHeuristic(float a, float b) { return a * a / (a * a + b * b); }
float maxOf(const glm::vec3& c) { return std::max({c.x, c.y, c.z}); }

// Where a ray meets an area light's lit face before tMax: the distance.
std::optional<float> hitArea(const Light& l, const Ray& ray, float tMax) {
  const glm::vec3 n = glm::cross(l.u, l.v);
  const float facing = glm::dot(ray.d, n);
  if (!(facing < 0.0f)) return std::nullopt;
  const glm::vec3 corner = l.position - 0.5f * (l.u + l.v);
  const float t = glm::dot(corner - ray.o, n) / facing;
  if (!(t > 0.0f && t < tMax)) return std::nullopt;
  const glm::vec3 q = ray.o + t * ray.d - corner;
  const float nn = glm::dot(n, n);
  const float a = glm::dot(glm::cross(q, l.v), n) / nn, b = glm::dot(glm::cross(l.u, q), n) / nn;
  if (a < 0.0f || a > 1.0f || b < 0.0f || b > 1.0f) return std::nullopt;
  return t;
}

}  // namespace

PathTracer::PathTracer(const Scene& scene, const Bvh& bvh, const EnvironmentLight* sky, const FrameSettings& frame,
                       const EffectPlan& plan)
    : scene_(scene),
      bvh_(bvh),
      plan_(plan),
      maxBounces_(frame.tracing.maxBounces),
      emitters_(scene.geometry, plan),
      sky_(sky),
      perBounce_(kFirstLightPair + static_cast<int>(scene.lights.size())) {
  for (const Light& l : scene.lights) {
    lightArea_.push_back(l.type == LightType::kArea ? glm::length(glm::cross(l.u, l.v)) : 0.0f);
  }
}

glm::vec3 PathTracer::escaped(const glm::vec3& d, float bsdfPdf) const {
  if (!plan_.environment) return scene_.background;
  const glm::vec3 radiance = scene_.environment->radiance(d);
  if (!sky_ || !(bsdfPdf > 0.0f)) return radiance;
  return radiance * powerHeuristic(bsdfPdf, sky_->pdf(d));
}

const glm::vec3& PathTracer::shadowFrom(const Vertex& v, const glm::vec3& d) const {
  if (glm::dot(d, v.s.ng) > 0.0f) return v.outside;
  if (!v.lifted) {
    const Geometry::LiftedPoint p = scene_.geometry.lifted(v.hit, v.s);
    v.lifted = offsetRayOrigin(p.p, p.error, v.s.ng);
  }
  return *v.lifted;
}

std::optional<PathTracer::LightSample> PathTracer::sampleLight(const Vertex& v, int light, const glm::vec2& u) const {
  const Light& l = scene_.lights[static_cast<std::size_t>(light)];
  const glm::vec3& p = v.s.p;
  switch (l.type) {
    case LightType::kDirectional:
      return LightSample{-l.direction, kInfinity, kPi * l.color, 0.0f};
    case LightType::kPoint:
    case LightType::kSpot: {
      const glm::vec3 to = l.position - p;
      const float d = glm::length(to);
      if (!(d > 0.0f)) return std::nullopt;
      const glm::vec3 wi = to / d;
      glm::vec3 intensity = plan_.attenuation ? attenuate(l.color, l.attenuation, d) : l.color / l.attenuation.x;
      if (l.type == LightType::kSpot) intensity *= spotFactor(l.direction, l.cosInner, l.cosOuter, wi);
      return LightSample{wi, d, kPi * intensity, 0.0f};
    }
    case LightType::kArea: {
      const float area = lightArea_[static_cast<std::size_t>(light)];
      const glm::vec3 q = l.position + (u.x - 0.5f) * l.u + (u.y - 0.5f) * l.v;
      const glm::vec3 to = q - p;
      const float d = glm::length(to);
      const glm::vec3 wi = to / d;
      const float cosE = -glm::dot(wi, glm::cross(l.u, l.v)) / area;
      if (!(d > 0.0f) || !(cosE > 0.0f)) return std::nullopt;
      return LightSample{wi, d, kPi * l.color / area, d * d / (cosE * area)};
    }
    case LightType::kSphere: {
      const std::optional<SphereLightView> view = SphereLightView::from(l.position, l.radius, p);
      if (!view) return std::nullopt;
      const SphereLightView::Sample s = view->sample(Stratum{0.0f, 1.0f, 0.0f, 1.0f}, u);
      return LightSample{s.direction, s.distance, l.color / (l.radius * l.radius), 1.0f / view->solidAngle()};
    }
  }
  return std::nullopt;
}

glm::vec3 PathTracer::contribution(const Vertex& v, const Bsdf& bsdf, const LightSample& l, bool last,
                                   RayStats& stats) const {
  const float cosI = glm::dot(l.wi, v.s.ns);
  if (!(cosI > 0.0f) || l.arriving == glm::vec3(0.0f)) return glm::vec3(0.0f);
  const glm::vec3 f = bsdf.eval(l.wi);
  if (f == glm::vec3(0.0f)) return f;
  ++stats.shadow;
  if (bvh_.occluded(Ray(shadowFrom(v, l.wi), l.wi), l.distance)) {
    ++stats.shadowBlocked;
    return glm::vec3(0.0f);
  }
  if (l.pdf == 0.0f) return f * cosI * l.arriving;  // a delta light
  return f * cosI * l.arriving * ((last ? 1.0f : powerHeuristic(l.pdf, bsdf.pdf(l.wi))) / l.pdf);
}

glm::vec3 PathTracer::directLight(const Vertex& v, const Bsdf& bsdf, const SampleKey& key, int bounce, bool last,
                                  RayStats& stats) const {
  glm::vec3 sum(0.0f);
  for (int i = 0; i < static_cast<int>(scene_.lights.size()); ++i) {
    if (!plan_.lights[static_cast<std::size_t>(i)]) continue;
    const std::optional<LightSample> l = sampleLight(v, i, key.stratified(pair(bounce, kFirstLightPair + i)));
    ++stats.lightSamples;
    if (l) sum += contribution(v, bsdf, *l, last, stats);
  }
  if (sky_) {
    ++stats.lightSamples;
    const EnvironmentLight::Sample s = sky_->sample(key.stratified(pair(bounce, kSkyPair)));
    if (s.pdf > 0.0f) {
      sum += contribution(v, bsdf, {s.direction, kInfinity, scene_.environment->radiance(s.direction), s.pdf}, last,
                          stats);
    }
  }
  if (!emitters_.empty()) {
    ++stats.lightSamples;
    const std::optional<Emitters::Seen> l =
        emitters_.seenFrom(scene_, plan_, v.s.p, key.stratified(pair(bounce, kEmitterPair)));
    if (l) sum += contribution(v, bsdf, {l->wi, l->distance, l->radiance, l->pdf}, last, stats);
  }
  return sum;
}

glm::vec3 PathTracer::lightsAlong(const Ray& ray, float tMax, float bsdfPdf) const {
  glm::vec3 sum(0.0f);
  for (std::size_t i = 0; i < scene_.lights.size(); ++i) {
    const Light& l = scene_.lights[i];
    if (!plan_.lights[i]) continue;
    float lightPdf = 0.0f;
    glm::vec3 radiance(0.0f);
    if (l.type == LightType::kArea) {
      const std::optional<float> t = hitArea(l, ray, tMax);
      if (!t) continue;
      const float cosE = -glm::dot(ray.d, glm::cross(l.u, l.v)) / lightArea_[i];
      lightPdf = *t * *t / (cosE * lightArea_[i]);
      radiance = kPi * l.color / lightArea_[i];
    } else if (l.type == LightType::kSphere) {
      const std::optional<SphereLightView> view = SphereLightView::from(l.position, l.radius, ray.o);
      if (!view || !intersectSphere(Sphere{l.position, l.radius, 0}, ray, tMax)) continue;
      lightPdf = 1.0f / view->solidAngle();
      radiance = l.color / (l.radius * l.radius);
    } else {
      continue;
    }
    sum += radiance * (bsdfPdf > 0.0f ? powerHeuristic(bsdfPdf, lightPdf) : 1.0f);
  }
  return sum;
}

glm::vec3 PathTracer::emittedAt(const Ray& ray, const Hit& hit, const SurfaceHit& s, const Material& m, float bsdfPdf,
                                bool weigh) const {
  const glm::vec3 radiance = surfaceEmission(scene_, m, s.uv);
  if (!weigh || !(bsdfPdf > 0.0f)) return radiance;
  const float cosE = std::abs(glm::dot(s.ng, ray.d));
  const float lightPdf = hit.t * hit.t / (cosE * emitters_.area());
  return radiance * powerHeuristic(bsdfPdf, lightPdf);
}

glm::vec3 PathTracer::radiance(const Ray& cameraRay, const SampleKey& key, RayStats& stats, First first,
                               float* firstDistance) const {
  ++stats.primary;
  ++stats.paths;
  glm::vec3 sum(0.0f), throughput(1.0f);
  Ray ray = cameraRay;
  bool inside = false;
  float bsdfPdf = 0.0f;  // the density the last bounce drew the ray with (0: the camera's, or a delta lobe)
  int bounce = 0;        // the bounce rays traced
  for (;; ++bounce) {
    const std::optional<Hit> hit = bvh_.intersect(ray, kInfinity);
    if (bounce == 0 && firstDistance) *firstDistance = hit ? hit->t : kInfinity;
    if (bounce > 0) sum += throughput * lightsAlong(ray, hit ? hit->t : kInfinity, bsdfPdf);
    if (!hit) {
      sum += throughput * escaped(ray.d, bounce > 0 ? bsdfPdf : 0.0f);
      break;
    }
    const std::uint32_t material = scene_.geometry.materialOf(hit->prim);
    const Material& m = scene_.materials[material];
    const MaterialEffects& e = plan_.materials[material];
    const SurfaceHit s = scene_.geometry.surface(ray, *hit, e.textured, plan_.vertexColors);
    if (e.emits && (bounce > 0 || first == First::kSeen))
      sum += throughput * emittedAt(ray, *hit, s, m, bsdfPdf, bounce > 0);
    const Bsdf bsdf(m, surfaceColor(scene_, m, e, s, plan_.vertexColors), s.ns, s.ng, -ray.d,
                    inside ? m.ior : 1.0f / m.ior);
    if (bsdf.black()) break;
    const Vertex v{s, *hit, offsetRayOrigin(s.p, s.error, s.ng), std::nullopt};
    const bool last = bounce >= maxBounces_;
    if (bsdf.smooth()) sum += throughput * directLight(v, bsdf, key, bounce, last, stats);
    if (last) break;
    const bool roulette = bounce + 1 >= kRouletteFrom;
    const glm::vec2 lobeAndRoulette =
        roulette || bsdf.choosesLobe() ? key.stratified(pair(bounce, kLobePair)) : glm::vec2(0.0f);
    const std::optional<Bsdf::Sample> next =
        bsdf.sample(lobeAndRoulette.x, key.stratified(pair(bounce, kDirectionPair)));
    if (!next) break;
    throughput *= next->weight;
    if (roulette) {
      const float survive = std::min(0.95f, maxOf(throughput));
      if (!(lobeAndRoulette.y < survive)) break;
      throughput /= survive;
    }
    if (!allFinite(throughput)) break;
    ++(next->transmitted ? stats.refraction : stats.reflection);
    ++stats.pathBounces;
    ray = Ray(next->transmitted ? offsetRayOrigin(s.p, s.error, -s.ng) : v.outside, next->wi);
    inside = inside != next->transmitted;
    bsdfPdf = next->pdf;
  }
  stats.longestPath = std::max(stats.longestPath, static_cast<std::uint64_t>(bounce));
  return sum;
}

}  // namespace glint
