#include "common/render/bsdf.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/math/basis.h"
#include "common/math/circular.h"
#include "common/math/power.h"
#include "common/scene/shading.h"
#include "common/render/glossy_lobe.h"
#include "common/render/optics.h"

namespace glint {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kTwoPi = 6.283185307179586f;

float maxOf(const glm::vec3& c) { return std::max({c.x, c.y, c.z}); }

// The unit vector at polar cosine `cosTheta` and azimuth 2 pi u around n.
glm::vec3 around(const glm::vec3& n, float cosTheta, float u) {
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  const SineCosine phi = turn(u);
  glm::vec3 t, b;
  orthonormalBasis(n, t, b);
  return glm::normalize(sinTheta * phi.cos * t + sinTheta * phi.sin * b + cosTheta * n);
}

// GGX's normal distribution D(h) at cos theta_h, and Smith's masking G1 of
// a direction at cosine c to the normal (Walter et al. 2007, eq. 33, 34).
float ggxD(float cosH, float alpha) {
  const float a2 = alpha * alpha;
  const float k = cosH * cosH * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * k * k);
}
float smithG1(float c, float alpha) {
  const float a2 = alpha * alpha;
  return 2.0f * c / (c + std::sqrt(a2 + (1.0f - a2) * c * c));
}

}  // namespace

LobeWeights lobeWeights(const Material& m, const glm::vec3& color) {
  LobeWeights w{glsl::diffuseAlbedo(color, m.diffuse, m.specular, m.reflectivity, m.transparency),
                glsl::specularWeight(color, m.diffuse, m.specular, m.reflectivity, m.transparency), m.reflectivity,
                m.transparency};
  const float sum = glsl::lobeSum(color, m.diffuse, m.specular, m.reflectivity, m.transparency);
  if (sum > 1.0f) {
    w.reflectivity /= sum;
    w.transparency /= sum;
  }
  return w;
}

Bsdf::Bsdf(const Material& m, const glm::vec3& color, const glm::vec3& ns, const glm::vec3& ng, const glm::vec3& wo,
           float eta)
    : ns_(ns),
      ng_(ng),
      wo_(wo),
      cosO_(std::max(glm::dot(wo, ns), 0.0f)),
      shininess_(m.shininess),
      alpha_(m.roughness * m.roughness),
      eta_(eta) {
  const LobeWeights w = lobeWeights(m, color);
  albedo_ = w.albedo;
  specular_ = w.specular;
  reflectivity_ = w.reflectivity;
  transparency_ = w.transparency;
  const bool rough = m.roughness > 0.0f;
  const float d = maxOf(albedo_), g = rough ? reflectivity_ : 0.0f, r = rough ? 0.0f : reflectivity_;
  total_ = d + specular_ + reflectivity_ + transparency_;
  const float inv = total_ > 0.0f ? 1.0f / total_ : 0.0f;
  pDiffuse_ = d * inv;
  pSpecular_ = specular_ * inv;
  pGlossy_ = g * inv;
  pMirror_ = r * inv;
  pDielectric_ = transparency_ * inv;
}

glm::vec3 Bsdf::glossy(const glm::vec3& wi, float& pdf) const {
  const glm::vec3 h = glm::normalize(wo_ + wi);
  const float cosH = glm::dot(h, ns_);
  const float cosI = glm::dot(wi, ns_);
  const float woH = glm::dot(wo_, h);
  if (cosH <= 0.0f || woH <= 0.0f || cosO_ <= 0.0f) return glm::vec3(0.0f);
  const float d = ggxD(cosH, alpha_);
  pdf = d * cosH / (4.0f * woH);
  const float g = smithG1(cosO_, alpha_) * smithG1(cosI, alpha_);
  return glm::vec3(reflectivity_ * d * g / (4.0f * cosO_ * cosI));
}

glm::vec3 Bsdf::eval(const glm::vec3& wi) const {
  const float cosI = glm::dot(wi, ns_);
  if (cosI <= 0.0f || glm::dot(wi, ng_) <= 0.0f) return glm::vec3(0.0f);
  glm::vec3 f = albedo_ * (1.0f / kPi);
  if (pSpecular_ > 0.0f) {
    const float c = glm::dot(reflect(-wo_, ns_), wi);
    if (c > 0.0f) f += specular_ * (shininess_ + 2.0f) / kTwoPi * power(c, shininess_);
  }
  if (pGlossy_ > 0.0f) {
    float unused = 0.0f;
    f += glossy(wi, unused);
  }
  return f;
}

float Bsdf::pdf(const glm::vec3& wi) const {
  const float cosI = glm::dot(wi, ns_);
  if (cosI <= 0.0f || glm::dot(wi, ng_) <= 0.0f) return 0.0f;
  float p = pDiffuse_ * cosI / kPi;
  if (pSpecular_ > 0.0f) {
    const float c = glm::dot(reflect(-wo_, ns_), wi);
    if (c > 0.0f) p += pSpecular_ * (shininess_ + 1.0f) / kTwoPi * power(c, shininess_);
  }
  if (pGlossy_ > 0.0f) {
    float g = 0.0f;
    glossy(wi, g);
    p += pGlossy_ * g;
  }
  return p;
}

std::optional<Bsdf::Sample> Bsdf::smoothSample(const glm::vec3& wi) const {
  const float p = pdf(wi);
  if (!(p > 0.0f)) return std::nullopt;
  return Sample{wi, eval(wi) * (glm::dot(wi, ns_) / p), p, false};
}

bool Bsdf::choosesLobe() const {
  const int lobes = (pDiffuse_ > 0.0f) + (pSpecular_ > 0.0f) + (pGlossy_ > 0.0f) + (pMirror_ > 0.0f) +
                    (pDielectric_ > 0.0f);
  return lobes > 1;
}

// Cosine-weighted. Where the Lambertian lobe is the only one eval() sees, f
// cos / pdf is the albedo over the lobe's chance whatever the direction.
std::optional<Bsdf::Sample> Bsdf::diffuseSample(const glm::vec2& u) const {
  const glm::vec3 wi = around(ns_, std::sqrt(u.x), u.y);
  if (pSpecular_ > 0.0f || pGlossy_ > 0.0f) return smoothSample(wi);
  const float cosI = glm::dot(wi, ns_);
  if (cosI <= 0.0f || glm::dot(wi, ng_) <= 0.0f) return std::nullopt;
  return Sample{wi, albedo_ / pDiffuse_, pDiffuse_ * cosI / kPi, false};
}

std::optional<Bsdf::Sample> Bsdf::sample(float pick, const glm::vec2& u) const {
  if (pick < pDiffuse_) return diffuseSample(u);
  pick -= pDiffuse_;
  if (pick < pSpecular_) {
    const float cosAlpha = power(u.x, 1.0f / (shininess_ + 1.0f));
    return smoothSample(around(reflect(-wo_, ns_), cosAlpha, u.y));
  }
  pick -= pSpecular_;
  if (pick < pGlossy_) return smoothSample(reflect(-wo_, ggxMicrofacetNormal(ns_, alpha_, u)));
  pick -= pGlossy_;
  const glm::vec3 mirror = mirrorDirection(-wo_, ns_, ng_);
  if (pick < pMirror_) return Sample{mirror, glm::vec3(reflectivity_ / pMirror_), 0.0f, false};
  if (!(pDielectric_ > 0.0f)) return std::nullopt;
  // The dielectric: the Fresnel share reflected, the rest refracted (the
  // choice between them by u.x, so that each keeps the lobe's weight).
  std::optional<glm::vec3> t = refract(-wo_, ns_, eta_);
  if (t && glm::dot(*t, ng_) >= 0.0f) t = refract(-wo_, ng_, eta_);
  const float fresnel = t ? fresnelDielectric(cosO_, eta_) : 1.0f;
  const glm::vec3 weight(transparency_ / pDielectric_);
  if (u.x < fresnel) return Sample{mirror, weight, 0.0f, false};
  return Sample{*t, weight, 0.0f, true};
}

}  // namespace glint
