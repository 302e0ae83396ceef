#pragma once

#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/scene/material.h"

namespace glint {

// A material read as a BSDF, for path transport (docs/scene-format.md, "The
// material as light sees it"). Its lobes, each weighted by its term:
//  - diffuse: Lambertian, albedo colour x diffuse (f = albedo / pi);
//  - specular: the normalised Phong lobe around the mirror direction,
//    f = specular (h + 2) / (2 pi) cos^h (Lafortune and Willems 1994), which
//    reflects at most `specular` of what arrives;
//  - reflectivity: a mirror, or with roughness > 0 the GGX microfacet lobe
//    (Walter et al. 2007, alpha = roughness^2, Smith's shadowing);
//  - transparency: a smooth dielectric of index `ior`, reflecting the
//    Fresnel share and refracting the rest.
// Energy is conserved by renormalising: where the largest channel of the
// albedo plus specular, reflectivity and transparency exceeds 1, all four
// are divided by that sum. The mirror and the dielectric are delta lobes:
// only sample() produces them.
// The lobes' weights of a material whose colour at a point is `color`,
// renormalised as the class comment says: the diffuse albedo and the
// specular, reflectivity and transparency terms.
struct LobeWeights {
  glm::vec3 albedo;
  float specular, reflectivity, transparency;
};
LobeWeights lobeWeights(const Material& m, const glm::vec3& color);

class Bsdf {
 public:
  // At a point of unit shading normal ns and geometric normal ng (both on
  // the side of the unit direction toward the viewer, wo), the surface's
  // colour there `color`; eta: the index ratio a refracted ray crosses
  // (outside over inside, or its inverse leaving).
  Bsdf(const Material& m, const glm::vec3& color, const glm::vec3& ns, const glm::vec3& ng, const glm::vec3& wo,
       float eta);

  // Whether every lobe is zero: the surface absorbs all.
  bool black() const { return total_ <= 0.0f; }
  // Whether some lobe that eval() sees is there (light sampling helps).
  bool smooth() const { return pDiffuse_ + pSpecular_ + pGlossy_ > 0.0f; }
  // Whether sample()'s `pick` matters: more than one lobe is there.
  bool choosesLobe() const;

  // f(wo, wi) of the non-delta lobes, and the probability density (solid
  // angle) with which sample() draws wi.
  glm::vec3 eval(const glm::vec3& wi) const;
  float pdf(const glm::vec3& wi) const;

  struct Sample {
    glm::vec3 wi;
    glm::vec3 weight;   // f cos / pdf: what the path's throughput is multiplied by
    float pdf;          // of a non-delta lobe's wi (for MIS); 0 for a delta lobe
    bool transmitted;   // wi crossed the surface
  };
  // A direction drawn from the lobes: `pick` chooses a lobe, u the direction.
  // None where the drawn direction leaves below the surface (absorbed).
  std::optional<Sample> sample(float pick, const glm::vec2& u) const;

 private:
  glm::vec3 glossy(const glm::vec3& wi, float& pdf) const;
  std::optional<Sample> smoothSample(const glm::vec3& wi) const;
  std::optional<Sample> diffuseSample(const glm::vec2& u) const;

  glm::vec3 ns_, ng_, wo_;
  float cosO_;  // wo . ns
  glm::vec3 albedo_;
  float specular_, shininess_, reflectivity_, alpha_, transparency_, eta_;
  float total_;
  // Each lobe's chance of being drawn: diffuse, Phong, GGX, mirror, dielectric.
  float pDiffuse_, pSpecular_, pGlossy_, pMirror_, pDielectric_;
};

}  // namespace glint
