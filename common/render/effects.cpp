#include "common/render/effects.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "common/render/mask_rule.h"

namespace glint {
namespace {

// True when the geometry cannot cast a shadow on itself: one sphere alone,
// or triangles that all lie in one plane (a lit point of a convex or planar
// surface never sees that surface between itself and a light in front).
bool selfShadowFree(const Geometry& g) {
  if (g.triangles().empty()) return g.spheres().size() <= 1;
  if (!g.spheres().empty()) return false;
  const auto& tris = g.triangles();
  const auto& pos = g.positions();
  const glm::vec3 p0 = pos[tris[0].v[0]];
  const glm::vec3 n = glm::normalize(glm::cross(pos[tris[0].v[1]] - p0, pos[tris[0].v[2]] - p0));
  float scale = 0.0f;
  for (const Triangle& t : tris) {
    for (std::uint32_t v : t.v) scale = std::max(scale, glm::length(pos[v] - p0));
  }
  for (const Triangle& t : tris) {
    for (std::uint32_t v : t.v) {
      if (std::abs(glm::dot(pos[v] - p0, n)) > 1e-6f * scale) return false;
    }
  }
  return true;
}

bool hasPositive(const glm::vec3& c) { return c.x > 0.0f || c.y > 0.0f || c.z > 0.0f; }

}  // namespace

EffectPlan EffectPlan::derive(const Scene& scene, const FrameSettings& frame) {
  EffectPlan plan;
  const bool secondary = frame.tracing.maxDepth > 1;
  const float minWeight = frame.tracing.minWeight;
  for (const Material& m : scene.materials) {
    MaterialEffects e;
    e.direct = m.diffuse > 0.0f || m.specular > 0.0f;
    e.specular = m.specular > 0.0f;
    e.emits = hasPositive(m.emission);
    e.textured = (m.texture >= 0 && scene.textures[m.texture].type != TextureType::kSolid) ||
                 (e.emits && m.emissionTexture >= 0);
    // Total internal reflection hands the transparent weight to the reflected
    // ray; it can only happen when the material's index differs from air's.
    const bool tir = m.transparency > 0.0f && m.ior != 1.0f;
    const float reflected = m.reflectivity + (tir ? m.transparency : 0.0f);
    e.reflects = secondary && reflected > 0.0f && reflected >= minWeight;
    e.refracts = secondary && m.transparency > 0.0f && m.transparency >= minWeight;
    e.glossy = e.reflects && m.roughness > 0.0f;
    plan.reflection = plan.reflection || e.reflects;
    plan.refraction = plan.refraction || e.refracts;
    plan.glossyReflection = plan.glossyReflection || e.glossy;
    plan.textures = plan.textures || e.textured;
    plan.emission = plan.emission || e.emits;
    plan.materials.push_back(e);
  }
  bool anyLight = false;
  bool anySoft = false;
  for (const Light& l : scene.lights) {
    const bool active = hasPositive(l.color);
    plan.lights.push_back(active);
    anyLight = anyLight || active;
    anySoft = anySoft || (active && softLight(l));
    if (active && (l.attenuation.y != 0.0f || l.attenuation.z != 0.0f)) plan.attenuation = true;
  }
  bool anyDirect = false;
  for (const MaterialEffects& e : plan.materials) anyDirect = anyDirect || e.direct;
  // Under path transport an emitting surface lights the others as a light
  // does (next-event estimation), with an area light's penumbra.
  const bool emittersLight = frame.tracing.transport == Transport::kPath && plan.emission;
  plan.shadows = (anyLight || emittersLight) && anyDirect && !selfShadowFree(scene.geometry);
  plan.softShadows = plan.shadows && (anySoft || emittersLight);
  plan.depthOfField = frame.camera.aperture > 0.0f;
  plan.environment = scene.environment != nullptr;
  plan.vertexColors = !scene.geometry.colors().empty();
  plan.antialiasing =
      frame.sampling.samples > 1 || frame.sampling.pattern != SamplePattern::kRegular;
  bool scatters = false;
  for (const Material& m : scene.materials) {
    scatters = scatters || m.diffuse > 0.0f || m.specular > 0.0f || m.reflectivity > 0.0f || m.transparency > 0.0f;
  }
  const bool lit = anyLight || plan.emission || plan.environment || hasPositive(scene.background);
  plan.indirectLight = frame.tracing.transport == Transport::kPath && frame.tracing.maxBounces > 0 && scatters && lit;
  return plan;
}

std::vector<NamedEffect> namedEffects(const EffectPlan& plan) {
  return {{"shadows", plan.shadows},   {"reflection", plan.reflection}, {"refraction", plan.refraction},
          {"textures", plan.textures}, {"emission", plan.emission},     {"vertex_colors", plan.vertexColors},
          {"attenuation", plan.attenuation}, {"antialiasing", plan.antialiasing}, {"soft_shadows", plan.softShadows},
          {"depth_of_field", plan.depthOfField}, {"glossy_reflection", plan.glossyReflection},
          {"environment", plan.environment}, {"indirect_light", plan.indirectLight}};
}

nlohmann::json toJson(const EffectPlan& plan) {
  nlohmann::json j = nlohmann::json::object();
  for (const NamedEffect& e : namedEffects(plan)) j[e.name] = e.needed;
  int active = 0;
  for (bool l : plan.lights) active += l ? 1 : 0;
  j["active_lights"] = active;
  return j;
}

bool rasterShadows(const Scene& scene, const EffectPlan& plan, const MaskSettings& mask) {
  if (!plan.shadows || mask.shadowMap <= 0 || mask.rule == MaskRule::kAll) return false;
  bool punctual = false;  // soft lights: client/raster/penumbra_proof.h
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    punctual = punctual || (plan.lights[i] && !softLight(scene.lights[i]));
  }
  if (!punctual) return false;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    if (plan.materials[i].direct && !materialMasked(scene.materials[i], mask)) return true;
  }
  return false;
}

}  // namespace glint
