#include "common/render/tracer.h"

#include <numbers>

#include <glm/geometric.hpp>

#include "common/math/float_bits.h"
#include "common/render/bsdf.h"
#include "common/render/glossy_lobe.h"
#include "common/render/optics.h"
#include "common/render/sphere_light.h"
#include "common/render/surface_terms.h"
#include "common/scene/shading.h"

namespace glint {

Tracer::Tracer(const Scene& scene, const Bvh& bvh, const FrameSettings& frame, const EffectPlan& plan,
               const IrradianceField* field)
    : scene_(scene),
      bvh_(bvh),
      tracing_(frame.tracing),
      plan_(plan),
      environment_(plan.environment ? scene.environment.get() : nullptr),
      field_(field) {
  for (const Light& l : scene.lights) {
    const int count = softLightSamples(l, frame.sampling.lightSamples);
    areas_.push_back(l.type == LightType::kArea ? std::optional<AreaLightPoints>(std::in_place, l, count)
                                                : std::nullopt);
    sphereStrata_.emplace_back();
    for (int k = 0; l.type == LightType::kSphere && k < count; ++k) {
      sphereStrata_.back().push_back(jitteredStratum(count, k));
    }
    lightDimensions_.push_back(lightDimensionsPerDepth_);
    if (softLight(l)) lightDimensionsPerDepth_ += 2 * count;
  }
  if (!field) return;
  patches_ = EmitterPatches::of(scene, plan, frame.sampling.lightSamples);
  if (!patches_) {
    emitters_.emplace(scene.geometry, plan);
    return;
  }
  for (const EmitterPatches::Patch& p : patches_->patches()) {
    patchDimensions_.push_back(lightDimensionsPerDepth_);
    lightDimensionsPerDepth_ += 2 * static_cast<int>(p.strata.size());
  }
}

int Tracer::lightDimension(int depth, int offset) const {
  return SampleKey::kFirstLightDimension + (depth - 1) * lightDimensionsPerDepth_ + offset;
}

int Tracer::lobeDimension(int depth) const {
  return SampleKey::kFirstLightDimension + tracing_.maxDepth * lightDimensionsPerDepth_ + 2 * (depth - 1);
}

glm::vec3 Tracer::reflectedDirection(const Ray& ray, const ShadingPoint& at, const Material& m,
                                     const MaterialEffects& e, const Path& path) const {
  if (!e.glossy) return mirrorDirection(ray.d, at.s.ns, at.s.ng);
  const int first = lobeDimension(at.depth);
  return glossyDirection(ray.d, at.s.ns, at.s.ng, m.roughness, {path.key.uniform(first), path.key.uniform(first + 1)});
}

glm::vec3 Tracer::radiance(const Ray& ray, const SampleKey& key, RayStats& stats) const {
  ++stats.primary;
  Path path{key, stats};
  return trace(ray, 1, 1.0f, false, path);
}

std::optional<glm::vec3> Tracer::radianceWithField(const Ray& ray, const SampleKey& key, RayStats& stats) const {
  ++stats.primary;
  Path path{key, stats};
  const glm::vec3 c = trace(ray, 1, 1.0f, false, path);
  if (path.undecided) return std::nullopt;
  return c;
}

glm::vec3 Tracer::fieldLight(const ShadingPoint& at, const Surface& f, Path& path) const {
  const glm::vec3& albedo = f.lobes->albedo;
  if (albedo == glm::vec3(0.0f)) return albedo;  // no lookup: nothing to decide
  const IrradianceField::Lookup light = field_->irradiance(at.s.p, at.s.ns, &bvh_);
  path.stats.shadow += static_cast<std::uint64_t>(light.sightRays);
  path.stats.shadowBlocked += static_cast<std::uint64_t>(light.sightBlocked);
  if (!light.decided) path.undecided = true;
  const glm::vec3 irradiance = light.irradiance + emitterIrradiance(at, path);
  return albedo * (irradiance * std::numbers::inv_pi_v<float>);
}

glm::vec3 Tracer::emitterIrradiance(const ShadingPoint& at, Path& path) const {
  if (patches_) {
    glm::vec3 sum(0.0f);
    for (int k = 0; k < static_cast<int>(patches_->patches().size()); ++k) sum += patchIrradiance(at, k, path);
    return sum;
  }
  if (emitters_->empty()) return glm::vec3(0.0f);
  // A pair of the key's points a depth, spread evenly over a pixel's samples.
  const glm::vec2 u = path.key.stratified(SampleKey::kFirstPathPair + at.depth - 1);
  const std::optional<Emitters::Seen> l = emitters_->seenFrom(scene_, plan_, at.s.p, u);
  if (!l) return glm::vec3(0.0f);
  const float cosI = glm::dot(l->wi, at.s.ns);
  if (!(cosI > 0.0f)) return glm::vec3(0.0f);
  ++path.stats.shadow;
  if (bvh_.occluded(Ray(shadowFrom(at, l->wi), l->wi), l->distance)) {
    ++path.stats.shadowBlocked;
    return glm::vec3(0.0f);
  }
  return l->radiance * (cosI / l->pdf);
}

glm::vec3 Tracer::patchIrradiance(const ShadingPoint& at, int patch, Path& path) const {
  const EmitterPatches::Patch& e = patches_->patches()[static_cast<std::size_t>(patch)];
  const glm::vec3 open = e.irradianceAt(at.s.p, at.s.ns);
  if (open == glm::vec3(0.0f)) return open;
  const auto target = [&](int k, const glm::vec2& u) -> std::optional<Direction> {
    const glm::vec3 q = e.at(stratumPoint(e.strata[static_cast<std::size_t>(k)], u));
    const glm::vec3 fromOrigin = q - shadowFrom(at, q - at.outside);
    const float distance = glm::length(fromOrigin);
    if (!(distance > 0.0f)) return std::nullopt;
    return Direction{fromOrigin / distance, distance * (1.0f - Emitters::kShortOfEmitter)};
  };
  const auto weight = [&](const Direction& d, float cosine) {
    return cosine * std::abs(glm::dot(e.normal, d.l)) / (d.distance * d.distance);
  };
  const int first = lightDimension(at.depth, patchDimensions_[static_cast<std::size_t>(patch)]);
  return open * visibleShare(at, first, static_cast<int>(e.strata.size()), path, target, weight);
}

glm::vec3 Tracer::lightIntensity(const glm::vec3& color, const glm::vec3& attenuation, float distance) const {
  if (!plan_.attenuation) return color / attenuation.x;  // constant: no distance term
  return attenuate(color, attenuation, distance);
}

glm::vec3 Tracer::emitted(const Material& m, const glm::vec2& uv) const { return surfaceEmission(scene_, m, uv); }

inline const glm::vec3& Tracer::shadowFrom(const ShadingPoint& at, const glm::vec3& d) const {
  if (glm::dot(d, at.s.ng) > 0.0f) return at.outside;
  if (!at.lifted) {
    const Geometry::LiftedPoint p = scene_.geometry.lifted(at.hit, at.s);
    at.lifted = offsetRayOrigin(p.p, p.error, at.s.ng);
  }
  return *at.lifted;
}

inline std::optional<Tracer::Direction> Tracer::towards(const ShadingPoint& at, const glm::vec3& position) const {
  const glm::vec3 toLight = position - at.s.p;
  const float distance = glm::length(toLight);
  if (!(distance > 0.0f)) return std::nullopt;
  return facing(at, Direction{toLight / distance, distance});
}

inline std::optional<Tracer::Direction> Tracer::facing(const ShadingPoint& at, const Direction& d) const {
  // A light behind the shading normal adds nothing. One behind the flat
  // triangle but before its smooth normal (a smooth mesh's terminator) is
  // left to the shadow ray from the lifted point.
  if (glm::dot(d.l, at.s.ns) <= 0.0f) return std::nullopt;
  return d;
}

inline void Tracer::addPhong(const ShadingPoint& at, const Surface& f, const Direction& d, const glm::vec3& lightI,
                             glm::vec3& result) const {
  if (f.lobes) {
    result += glsl::lobesReflect(lightI, f.lobes->albedo, f.lobes->specular, f.m.shininess, at.s.ns, d.l, at.toViewer);
    return;
  }
  result += phongDiffuse(lightI, f.color, f.m.diffuse, at.s.ns, d.l);
  if (f.e.specular) result += phongSpecular(lightI, f.m.specular, f.m.shininess, at.s.ns, d.l, at.toViewer);
}

inline void Tracer::addPunctualLight(const ShadingPoint& at, const Surface& f, int light, Path& path,
                                     glm::vec3& result) const {
  const Light& l = scene_.lights[static_cast<std::size_t>(light)];
  const bool directional = l.type == LightType::kDirectional;
  const std::optional<Direction> d =
      directional ? facing(at, Direction{-l.direction, kInfinity}) : towards(at, l.position);
  if (!d) return;
  glm::vec3 lightI = directional ? l.color : lightIntensity(l.color, l.attenuation, d->distance);
  if (l.type == LightType::kSpot) {
    const float share = spotFactor(l.direction, l.cosInner, l.cosOuter, d->l);
    if (share == 0.0f) return;
    lightI *= share;
  }
  if (plan_.shadows && blocked(at, l, path)) return;
  addPhong(at, f, *d, lightI, result);
}

inline bool Tracer::blocked(const ShadingPoint& at, const Light& l, Path& path) const {
  ++path.stats.shadow;
  bool hit = false;
  if (l.type == LightType::kDirectional) {
    hit = bvh_.occluded(Ray(shadowFrom(at, -l.direction), -l.direction), kInfinity);
  } else {
    const glm::vec3& from = shadowFrom(at, l.position - at.outside);
    const glm::vec3 fromOrigin = l.position - from;
    const float shadowDistance = glm::length(fromOrigin);
    hit = bvh_.occluded(Ray(from, fromOrigin / shadowDistance), shadowDistance);
  }
  if (hit) ++path.stats.shadowBlocked;
  return hit;
}

void Tracer::addAreaLight(const ShadingPoint& at, const Surface& f, int light, Path& path, glm::vec3& result) const {
  const Light& l = scene_.lights[static_cast<std::size_t>(light)];
  const AreaLightPoints& a = *areas_[static_cast<std::size_t>(light)];
  glm::vec3 lit{0.0f};
  for (const glm::vec3& c : a.centres) {
    const std::optional<Direction> d = a.lights(c, at.s.p) ? towards(at, c) : std::nullopt;
    if (d) addPhong(at, f, *d, lightIntensity(a.color, l.attenuation, d->distance), lit);
  }
  if (lit == glm::vec3(0.0f)) return;
  if (!plan_.shadows) {
    result += lit;
    return;
  }
  const auto target = [&](int k, const glm::vec2& u) -> std::optional<Direction> {
    const glm::vec3 q = a.jittered(k, u);
    const glm::vec3 fromOrigin = q - shadowFrom(at, q - at.outside);
    const float distance = glm::length(fromOrigin);
    if (!(distance > 0.0f) || !a.lights(q, at.s.p)) return std::nullopt;
    return Direction{fromOrigin / distance, distance};
  };
  const auto weight = [&](const Direction& d, float cosine) {
    return attenuate(glm::vec3(cosine), l.attenuation, d.distance).x;
  };
  const int first = lightDimension(at.depth, lightDimensions_[static_cast<std::size_t>(light)]);
  result += lit * visibleShare(at, first, static_cast<int>(a.strata.size()), path, target, weight);
}

void Tracer::addSphereLight(const ShadingPoint& at, const Surface& f, int light, Path& path, glm::vec3& result) const {
  const Light& l = scene_.lights[static_cast<std::size_t>(light)];
  const std::optional<Direction> d = towards(at, l.position);
  if (!d) return;
  glm::vec3 lit{0.0f};
  addPhong(at, f, *d, lightIntensity(l.color, l.attenuation, d->distance), lit);
  if (lit == glm::vec3(0.0f)) return;
  // A point in the ball sees no cone: the centre's light stands.
  const std::optional<SphereLightView> view =
      SphereLightView::from(l.position, l.radius, shadowFrom(at, l.position - at.outside));
  if (!plan_.shadows || !view) {
    result += lit;
    return;
  }
  const std::vector<Stratum>& strata = sphereStrata_[static_cast<std::size_t>(light)];
  const auto target = [&](int k, const glm::vec2& u) -> std::optional<Direction> {
    const SphereLightView::Sample s = view->sample(strata[static_cast<std::size_t>(k)], u);
    if (!(s.distance > 0.0f)) return std::nullopt;
    return Direction{s.direction, s.distance};
  };
  const auto weight = [](const Direction&, float cosine) { return cosine; };
  const int first = lightDimension(at.depth, lightDimensions_[static_cast<std::size_t>(light)]);
  result += lit * visibleShare(at, first, static_cast<int>(strata.size()), path, target, weight);
}

template <typename Target, typename Weight>
float Tracer::visibleShare(const ShadingPoint& at, int first, int count, Path& path, const Target& target,
                           const Weight& weight) const {
  float open = 0.0f;
  float total = 0.0f;
  for (int k = 0; k < count; ++k) {
    const std::optional<Direction> d =
        target(k, glm::vec2(path.key.uniform(first + 2 * k), path.key.uniform(first + 2 * k + 1)));
    if (!d) continue;
    const float cosine = glm::dot(d->l, at.s.ns);
    if (cosine <= 0.0f) continue;
    const float w = weight(*d, cosine);
    total += w;
    ++path.stats.shadow;
    if (bvh_.occluded(Ray(shadowFrom(at, d->l), d->l), d->distance)) {
      ++path.stats.shadowBlocked;
    } else {
      open += w;
    }
  }
  // No point faces the surface (a light at grazing incidence): the
  // unshadowed light stands, as the raster shades it.
  return total > 0.0f ? open / total : 1.0f;
}

glm::vec3 Tracer::shade(const ShadingPoint& at, const Material& m, const MaterialEffects& e, Path& path) const {
  const SurfaceHit& s = at.s;
  const glm::vec3 color = surfaceColor(scene_, m, e, s, plan_.vertexColors);
  const std::optional<LobeWeights> lobes = field_ ? std::optional(lobeWeights(m, color)) : std::nullopt;
  const Surface f{color, m, e, lobes ? &*lobes : nullptr};
  glm::vec3 result = field_ ? fieldLight(at, f, path) : phongAmbient(f.color, m.ambient);
  if (e.emits) result += emitted(m, s.uv);
  if (!e.direct) return result;
  for (int i = 0; i < static_cast<int>(scene_.lights.size()); ++i) {
    if (!plan_.lights[static_cast<std::size_t>(i)]) continue;
    if (areas_[static_cast<std::size_t>(i)]) {
      addAreaLight(at, f, i, path, result);
    } else if (scene_.lights[static_cast<std::size_t>(i)].type == LightType::kSphere) {
      addSphereLight(at, f, i, path, result);
    } else {
      addPunctualLight(at, f, i, path, result);
    }
  }
  return result;
}

glm::vec3 Tracer::trace(const Ray& ray, int depth, float weight, bool inside, Path& path) const {
  const std::optional<Hit> hit = bvh_.intersect(ray, kInfinity);
  if (!hit) return environment_ ? environment_->radiance(ray.d) : scene_.background;
  const std::uint32_t material = scene_.geometry.materialOf(hit->prim);
  const Material& m = scene_.materials[material];
  const MaterialEffects& e = plan_.materials[material];
  const SurfaceHit s = scene_.geometry.surface(ray, *hit, e.textured, plan_.vertexColors);
  const glm::vec3 outside = offsetRayOrigin(s.p, s.error, s.ng);
  const ShadingPoint at{s, *hit, outside, std::nullopt, -ray.d, depth};
  glm::vec3 color = shade(at, m, e, path);
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
    ++path.stats.reflection;
    color += kr * trace(Ray(outside, reflectedDirection(ray, at, m, e, path)), depth + 1, weight * kr, inside, path);
  }
  if (e.refracts && kt > 0.0f && weight * kt >= minWeight) {
    ++path.stats.refraction;
    color += kt * trace(Ray(offsetRayOrigin(s.p, s.error, -s.ng), refracted), depth + 1, weight * kt, !inside, path);
  }
  return color;
}

}  // namespace glint
