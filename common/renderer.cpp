#include "common/renderer.h"

#include <algorithm>
#include <cmath>

#include "common/finite.h"
#include "common/sampling.h"

namespace glint {

Renderer::Renderer(const PreparedScene& prepared, const FrameSettings& frame)
    : Renderer(prepared, frame, EffectPlan::derive(prepared.scene(), frame)) {}

Renderer::Renderer(const PreparedScene& prepared, const FrameSettings& frame, const EffectPlan& plan)
    : prepared_(prepared),
      frame_(frame),
      plan_(plan),
      camera_(frame.camera, frame.width, frame.height),
      filter_(frame.sampling.filter),
      tracer_(prepared.scene(), prepared.bvh(), frame_.tracing, plan_) {}

std::uint8_t toByte(float v) {
  const float c = std::clamp(v, 0.0f, 1.0f);  // NaN stays NaN; callers pass finite values
  return static_cast<std::uint8_t>(std::lround(c * 255.0f));
}

glm::vec3 Renderer::pixel(int x, int y, RayStats& stats) const {
  const SamplingSettings& sampling = frame_.sampling;
  glm::vec3 sum{0.0f};
  glm::vec3 unweighted{0.0f};
  float weightSum = 0.0f;
  int finiteCount = 0;
  for (int i = 0; i < sampling.samples; ++i) {
    glm::vec2 offset{0.5f};
    if (plan_.antialiasing) {
      const glm::vec2 u = samplePosition(sampling, x, y, i);
      offset = {0.5f + filter_.warp(u.x), 0.5f + filter_.warp(u.y)};
    }
    const Ray ray = camera_.generateRay({static_cast<float>(x) + offset.x,
                                         static_cast<float>(y) + offset.y});
    const glm::vec3 c = tracer_.radiance(ray, stats);
    if (!allFinite(c)) {
      ++stats.nonFiniteSamples;
      continue;
    }
    const float w = plan_.antialiasing ? filter_.sign(offset.x - 0.5f) * filter_.sign(offset.y - 0.5f) : 1.0f;
    sum += w * c;
    weightSum += w;
    unweighted += c;
    ++finiteCount;
  }
  if (finiteCount == 0) return prepared_.scene().background;
  // Negative lobes (Mitchell) can leave too little positive weight in a few
  // samples; the plain mean is the stable answer then.
  if (weightSum < 0.5f * static_cast<float>(finiteCount)) {
    return unweighted / static_cast<float>(finiteCount);
  }
  return sum / weightSum;
}

void Renderer::renderTile(const TileRect& rect, std::span<const std::uint8_t> mask,
                          std::vector<std::uint8_t>& rgb, RayStats& stats) const {
  std::size_t i = 0;
  for (int y = rect.y; y < rect.y + rect.height; ++y) {
    for (int x = rect.x; x < rect.x + rect.width; ++x, ++i) {
      if (!mask.empty() && !maskBit(mask, i)) continue;
      const glm::vec3 c = pixel(x, y, stats);
      rgb.push_back(toByte(c.r));
      rgb.push_back(toByte(c.g));
      rgb.push_back(toByte(c.b));
    }
  }
}

}  // namespace glint
