#include "common/render/irradiance_field.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "common/scene/shading.h"

namespace glint {
namespace {

// Probes along each axis: settings.probes along the longest side, the
// others in proportion to their length, at least kMinProbes.
glm::ivec3 probeCounts(const glm::vec3& extent, int probes) {
  const float longest = std::max({extent.x, extent.y, extent.z});
  glm::ivec3 counts;
  for (int a = 0; a < 3; ++a) {
    const float share = longest > 0.0f ? extent[a] / longest : 0.0f;
    counts[a] = std::max(FieldSettings::kMinProbes, static_cast<int>(std::lround(share * static_cast<float>(probes))));
  }
  return counts;
}

// A point's blend over the probes of its cell, as shading.glsl's functions
// weigh them.
struct Blend {
  glm::vec3 sum{0.0f};
  float weight = 0.0f;  // of the probes that see the point
  float share = 0.0f;   // before visibility
  float doubt = 0.0f;   // of the probes in doubt whether they see it
};

// The box the probes span: the bounds, a flat side (a scene of one plane)
// widened about its centre to one cell of the longest side's.
Bounds3 spanned(const Bounds3& bounds, int probes) {
  const glm::vec3 extent = bounds.extent();
  const float cell = std::max({extent.x, extent.y, extent.z}) / static_cast<float>(probes);
  const glm::vec3 half = 0.5f * glm::max(extent, glm::vec3(cell));
  return {bounds.centre() - half, bounds.centre() + half};
}

}  // namespace

FieldGrid::FieldGrid(const Bounds3& bounds, const FieldSettings& settings) : settings_(settings) {
  const Bounds3 box = spanned(bounds, settings.probes);
  counts_ = probeCounts(box.extent(), settings.probes);
  step_ = box.extent() / glm::vec3(counts_);
  origin_ = box.min + 0.5f * step_;
}

glm::vec3 FieldGrid::position(int probe) const {
  const glm::ivec3 cell(probe % counts_.x, (probe / counts_.x) % counts_.y, probe / (counts_.x * counts_.y));
  return origin_ + glm::vec3(cell) * step_;
}

float FieldGrid::maxDistance() const { return 2.0f * glm::length(step_); }

IrradianceField::IrradianceField(const Bounds3& bounds, const FieldSettings& settings)
    : grid_(bounds, settings), probes_(static_cast<std::size_t>(grid_.probeCount())) {}

void IrradianceField::writeProbe(const Probe& probe, std::span<float, kProbeFloats> out) {
  float* at = out.data();
  for (const glm::vec3& c : probe.irradiance) at = std::copy_n(&c.x, 3, at);
  for (const glm::vec2& m : probe.moments) at = std::copy_n(&m.x, 2, at);
}

IrradianceField::Probe IrradianceField::readProbe(std::span<const float, kProbeFloats> in) {
  Probe probe;
  const float* at = in.data();
  for (glm::vec3& c : probe.irradiance) {
    c = glm::vec3(at[0], at[1], at[2]);
    at += 3;
  }
  for (glm::vec2& m : probe.moments) {
    m = glm::vec2(at[0], at[1]);
    at += 2;
  }
  return probe;
}

int IrradianceField::texel(const glm::vec2& point) {
  const int x = std::clamp(static_cast<int>(point.x * kMapSide), 0, kMapSide - 1);
  const int y = std::clamp(static_cast<int>(point.y * kMapSide), 0, kMapSide - 1);
  return y * kMapSide + x;
}

IrradianceField::Lookup IrradianceField::irradiance(const glm::vec3& p, const glm::vec3& n, const Bvh* sight) const {
  const float minStep = std::min({step().x, step().y, step().z});
  // Looked up a little off the surface, so that the probes beside it on its
  // own side do not see it at a grazing distance.
  const glm::vec3 q = p + (0.25f * minStep) * n;
  const glm::vec3 at = glm::clamp((q - origin()) / step(), glm::vec3(0.0f), glm::vec3(counts() - 1));
  const glm::ivec3 base = glm::min(glm::ivec3(at), counts() - 2);
  const glm::vec3 alpha = at - glm::vec3(base);
  const float minVariance = (0.05f * minStep) * (0.05f * minStep);
  Blend blend;
  Lookup out;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 offset(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const int i = index(base + offset);
    const glm::vec3 toProbe = position(i) - q;
    const float d = glm::length(toProbe);
    const glm::vec3 dir = d > 0.0f ? toProbe / d : n;
    const glm::vec3 t = glm::mix(1.0f - alpha, alpha, glm::vec3(offset));
    const float share = glsl::probeShare(t.x * t.y * t.z, dir, n);
    const Probe& probe = probes_[static_cast<std::size_t>(i)];
    const glm::vec2 moments = probe.moments[static_cast<std::size_t>(texel(glsl::octahedralPoint(-dir)))];
    float v = glsl::probeVisibility(moments, d, minVariance);
    if (sight && v > 0.0f && d > 0.0f) {
      ++out.sightRays;
      if (sight->occluded(Ray(q, dir), d)) {
        ++out.sightBlocked;
        v = 0.0f;
      }
    }
    const float w = share * v;
    blend.sum += w * glsl::shIrradiance(probe.irradiance.data(), n);
    blend.weight += w;
    blend.share += share;
    if (!sight && glsl::visibilityInDoubt(v)) blend.doubt += share;
  }
  out.decided = blend.share > 0.0f && blend.weight >= kDecidedShare * blend.share &&
                blend.doubt <= kDoubtShare * blend.share;
  if (blend.weight > 0.0f) out.irradiance = blend.sum / blend.weight;
  return out;
}

}  // namespace glint
