#include "common/render/field_probes.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "common/base/compute_pool.h"
#include "common/base/error.h"
#include "common/math/circular.h"
#include "common/math/finite.h"
#include "common/render/path_tracer.h"
#include "common/render/sampling.h"
#include "common/scene/shading.h"

namespace glint {
namespace {

// The probes' keys: the probe's index as a pixel of a row no frame has.
constexpr int kFieldRow = -1;
// A probe's rays are uniform over the sphere: each over its density.
constexpr float kSphere = 4.0f * std::numbers::pi_v<float>;

// What a probe's rays add up before they are scaled.
struct ProbeSums {
  std::array<glm::vec3, 9> harmonics{};
  std::array<glm::vec2, IrradianceField::kMapTexels> moments{};
  std::array<int, IrradianceField::kMapTexels> rays{};
};

// Light arriving from direction wi, over the density it was drawn with,
// projected on the harmonics.
void addLight(ProbeSums& sums, const glm::vec3& wi, const glm::vec3& light, RayStats& stats) {
  if (!allFinite(light)) {
    ++stats.nonFiniteSamples;
    return;
  }
  for (int k = 0; k < 9; ++k) sums.harmonics[k] += light * glsl::shBasis(k, wi);
}

IrradianceField::Probe scaled(const ProbeSums& sums, int rays, float maxDistance) {
  IrradianceField::Probe probe;
  const float perRay = 1.0f / static_cast<float>(rays);
  for (int k = 0; k < 9; ++k) probe.irradiance[k] = sums.harmonics[k] * (glsl::cosineLobe(k) * perRay);
  for (int t = 0; t < IrradianceField::kMapTexels; ++t) {
    probe.moments[t] = sums.rays[t] > 0 ? sums.moments[t] / static_cast<float>(sums.rays[t])
                                        : glm::vec2(maxDistance, maxDistance * maxDistance);
  }
  return probe;
}

// The frame's settings with a bounce fewer: a probe's rays stand for a surface's first bounce.
FrameSettings probeFrame(FrameSettings frame) {
  frame.tracing.maxBounces = std::max(0, frame.tracing.maxBounces - 1);
  return frame;
}

}  // namespace

glm::vec3 octahedralDirection(const glm::vec2& point) {
  const float u = 2.0f * point.x - 1.0f;
  const float v = 2.0f * point.y - 1.0f;
  const float up = std::abs(u);
  const float vp = std::abs(v);
  const float signedDistance = 1.0f - (up + vp);
  const float r = 1.0f - std::abs(signedDistance);
  // The azimuth within the octant, as a fraction of a turn.
  const float azimuth = (r == 0.0f ? 1.0f : (vp - up) / r + 1.0f) * 0.125f;
  const SineCosine sc = turn(azimuth);
  const float z = std::copysign(1.0f - r * r, signedDistance);
  const float s = r * std::sqrt(std::max(2.0f - r * r, 0.0f));
  return {std::copysign(sc.cos, u) * s, std::copysign(sc.sin, v) * s, z};
}

ProbeTracer::ProbeTracer(const PreparedScene& prepared, const FrameSettings& frame, const FieldGrid& grid)
    : grid_(grid),
      probes_(probeFrame(frame)),
      plan_(EffectPlan::derive(prepared.scene(), probes_)),
      path_(prepared.scene(), prepared.bvh(), plan_.environment ? prepared.environmentLight() : nullptr, probes_,
            plan_),
      layout_(frame.sampling) {}

IrradianceField::Probe ProbeTracer::trace(int index, RayStats& stats) const {
  const glm::vec3 origin = grid_.position(index);
  const float maxDistance = grid_.maxDistance();
  const int rays = grid_.settings().rays;
  const SampleLayout::Pixel pixel = layout_.pixel(index, kFieldRow);
  ProbeSums sums;
  for (int r = 0; r < rays; ++r) {
    const SampleKey key = SampleLayout::key(pixel, r);
    const glm::vec2 point = key.stratified(SampleKey::kPixelPair);
    const Ray ray(origin, octahedralDirection(point));
    float hit = kInfinity;
    const glm::vec3 light = path_.radiance(ray, key, stats, PathTracer::First::kReflected, &hit);
    const float d = std::min(hit, maxDistance);
    const int texel = IrradianceField::texel(point);
    sums.moments[texel] += glm::vec2(d, d * d);
    ++sums.rays[texel];
    addLight(sums, ray.d, light * kSphere, stats);
  }
  return scaled(sums, rays, maxDistance);
}

void fillProbes(IrradianceField& field, const PreparedScene& prepared, const FrameSettings& frame, int first, int end,
                RayStats& stats, const ProbeProgress& progress) {
  const ProbeTracer tracer(prepared, frame, field.grid());
  std::mutex statsMutex;
  int filled = 0;
  computePool().parallelFor(static_cast<std::size_t>(end - first), [&](std::size_t i) {
    RayStats own;
    const int index = first + static_cast<int>(i);
    field.probe(index) = tracer.trace(index, own);
    std::lock_guard lock(statsMutex);
    stats += own;
    if (progress) progress(++filled, end - first);
  });
}

IrradianceField buildField(const PreparedScene& prepared, const FrameSettings& frame, const FieldSettings& settings,
                           RayStats& stats, const ProbeProgress& progress) {
  const Bounds3 bounds = prepared.scene().geometry.bounds();
  if (bounds.empty()) throw InputError("the irradiance field: the scene has no object to span");
  IrradianceField field(bounds, settings);
  fillProbes(field, prepared, frame, 0, field.probeCount(), stats, progress);
  return field;
}

}  // namespace glint
