#include "common/render/emitter_patches.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "common/scene/shading.h"

namespace glint {

glm::vec3 EmitterPatches::Patch::at(const glm::vec2& st) const {
  // Uniform over the triangle: b0 = 1 - sqrt(s), b1 = (1 - t) sqrt(s), b2 = t sqrt(s).
  const float r = std::sqrt(st.x);
  return corner + (r * (1.0f - st.y)) * edge1 + (r * st.y) * edge2;
}

glm::vec3 EmitterPatches::Patch::irradianceAt(const glm::vec3& p, const glm::vec3& n) const {
  return glsl::triangleIrradiance(radiance, corner, corner + edge1, corner + edge2, p, n);
}

int EmitterPatches::points() const {
  int n = 0;
  for (const Patch& p : patches_) n += static_cast<int>(p.strata.size());
  return n;
}

std::optional<EmitterPatches> EmitterPatches::of(const Scene& scene, const EffectPlan& plan, int points) {
  EmitterPatches result;
  if (!plan.emission) return result;
  const Geometry& g = scene.geometry;
  float total = 0.0f;
  for (std::uint32_t prim = 0; prim < g.primitiveCount(); ++prim) {
    const std::uint32_t material = g.materialOf(prim);
    if (!plan.materials[material].emits) continue;
    const Material& m = scene.materials[material];
    if (g.isSphere(prim) || m.emissionTexture >= 0 || result.patches_.size() == kMaxPatches) return std::nullopt;
    const Triangle& t = g.triangles()[prim];
    const auto& p = g.positions();
    Patch patch;
    patch.corner = p[t.v[0]];
    patch.edge1 = p[t.v[1]] - patch.corner;
    patch.edge2 = p[t.v[2]] - patch.corner;
    patch.normal = g.faceNormals()[prim];
    patch.radiance = m.emission;
    patch.area = 0.5f * glm::length(glm::cross(patch.edge1, patch.edge2));
    if (!(patch.area > 0.0f) || !std::isfinite(patch.area)) continue;
    total += patch.area;
    result.patches_.push_back(std::move(patch));
  }
  const float all = static_cast<float>(points > 0 ? points : kDefaultPoints);
  for (Patch& patch : result.patches_) {
    const int count = std::max(1, static_cast<int>(std::lround(all * patch.area / total)));
    for (int k = 0; k < count; ++k) patch.strata.push_back(jitteredStratum(count, k));
  }
  return result;
}

}  // namespace glint
