#include "common/render/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <new>
#include <stdexcept>

#include "common/image/encoding.h"
#include "common/image/flip_colour.h"
#include "common/math/finite.h"
#include "common/render/sampling.h"

namespace glint {

Renderer::Renderer(const PreparedScene& prepared, const FrameSettings& frame)
    : Renderer(prepared, frame, EffectPlan::derive(prepared.scene(), frame)) {}

Renderer::Renderer(const PreparedScene& prepared, const FrameSettings& frame, const EffectPlan& plan,
                   const IrradianceField* field)
    : prepared_(prepared),
      frame_(frame),
      plan_(plan),
      camera_(frame.camera, frame.width, frame.height),
      filter_(frame.sampling.filter),
      sampleLayout_(frame.sampling),
      tracer_(prepared.scene(), prepared.bvh(), frame_, plan_, field),
      withField_(field != nullptr) {
  if (frame.tracing.transport == Transport::kPath) {
    path_.emplace(prepared.scene(), prepared.bvh(), plan_.environment ? prepared.environmentLight() : nullptr, frame_,
                  plan_);
  } else if (field) {
    throw std::logic_error("an irradiance field is read under path transport only");
  }
}

glm::vec3 Renderer::fieldRadiance(const Ray& ray, const SampleKey& key, RayStats& stats) const {
  if (const std::optional<glm::vec3> c = tracer_.radianceWithField(ray, key, stats)) return *c;
  ++stats.fieldUndecided;
  return path_->radiance(ray, key, stats);
}

Ray Renderer::cameraRay(const glm::vec2& film, const SampleKey& key) const {
  if (!plan_.depthOfField) return camera_.generateRay(film);
  return camera_.generateRay(film, {key.uniform(SampleKey::kLensDimension), key.uniform(SampleKey::kLensDimension + 1)});
}

Renderer::CameraSample Renderer::cameraSample(int x, int y, const SampleLayout::Pixel& key, int sample) const {
  glm::vec2 offset{0.5f};
  if (plan_.antialiasing) {
    const glm::vec2 u = sampleLayout_.position(key, sample);
    offset = {0.5f + filter_.warp(u.x), 0.5f + filter_.warp(u.y)};
  }
  const float w = plan_.antialiasing ? filter_.sign(offset.x - 0.5f) * filter_.sign(offset.y - 0.5f) : 1.0f;
  const SampleKey sampleKey = SampleLayout::key(key, sample);
  const glm::vec2 film{static_cast<float>(x) + offset.x, static_cast<float>(y) + offset.y};
  return {cameraRay(film, sampleKey), w, sampleKey};
}

void Renderer::addSamples(int x, int y, int first, int end, PixelSamples& p, RayStats& stats) const {
  // The camera rays of a batch are made before any is traced: each is a
  // long chain of dependent multiplications, divisions and square roots,
  // which the processor then overlaps.
  constexpr int kBatch = 8;
  const SampleLayout::Pixel key = sampleLayout_.pixel(x, y);
  for (int from = first; from < end; from += kBatch) {
    std::array<CameraSample, kBatch> batch;
    const int count = std::min(kBatch, end - from);
    // Each made in place: assigned from a returned temporary, a sample is
    // written piecewise and read back whole, which stalls the processor's
    // store forwarding (about 4 % of the room's full trace, measured).
    for (int i = 0; i < count; ++i) new (&batch[i]) CameraSample(cameraSample(x, y, key, from + i));
    for (int i = 0; i < count; ++i) {
      const glm::vec3 c = radiance(batch[i].ray, batch[i].key, stats);
      if (!allFinite(c)) {
        ++stats.nonFiniteSamples;
        continue;
      }
      p.sum += batch[i].weight * c;
      p.weightSum += batch[i].weight;
      p.unweighted += c;
      ++p.finite;
    }
  }
}

void Renderer::addCentreSample(int x, int y, PixelSamples& p, RayStats& stats) const {
  constexpr int kCentreSample = -1;  // a key of its own, apart from the pattern's samples
  const SampleKey key = SampleLayout::key(sampleLayout_.pixel(x, y), kCentreSample);
  const glm::vec2 film{static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f};
  const glm::vec3 c = radiance(cameraRay(film, key), key, stats);
  if (!allFinite(c)) {
    ++stats.nonFiniteSamples;
    return;
  }
  p.sum += c;  // the filter's centre: a positive weight, 1 as every warped sample's
  p.weightSum += 1.0f;
  p.unweighted += c;
  ++p.finite;
}

glm::vec3 Renderer::resolve(const PixelSamples& p) const {
  if (p.finite == 0) return prepared_.scene().background;
  // Negative lobes (Mitchell) can leave too little positive weight in a few
  // samples; the plain mean is the stable answer then.
  if (p.weightSum < 0.5f * static_cast<float>(p.finite)) return p.unweighted / static_cast<float>(p.finite);
  return p.sum / p.weightSum;
}

glm::vec3 Renderer::pixel(int x, int y, RayStats& stats) const {
  PixelSamples p;
  addSamples(x, y, 0, frame_.sampling.samples, p, stats);
  return resolve(p);
}

// The adaptive patterns: a probe of every pixel, then the rest of its
// jittered samples where the probe differs from a neighbour's. The probes of
// the tile and of a one-pixel border are traced as needed: they depend on
// the pixel alone, so every tile split, thread count and server decides
// alike.
//  - adaptive: the probe is the pixel's first jittered sample (samples 1 to
//    n - 1 follow it), the 4 neighbours, a channel differing by more than
//    adaptiveThreshold.
//  - perceptual: the probe is a ray at the pixel's centre, where the raster
//    shades it and the best single estimate of a smooth pixel, the 8
//    neighbours, FLIP's colour term of the two colours as displayed above
//    perceptualThreshold: a difference the eye sees. A refined pixel is the
//    jittered pattern's own (its n samples; the probe, which the filter did
//    not draw, is left out).
void Renderer::renderAdaptive(const TileRect& rect, std::span<const std::uint8_t> mask, std::vector<glm::vec3>& out,
                              RayStats& stats) const {
  const bool perceptual = frame_.sampling.pattern == SamplePattern::kPerceptual;
  const Encoder encoder(frame_.output);
  const auto displayedLab = [&encoder](const glm::vec3& c) {
    return flipLab({encoder.displayed(c.r), encoder.displayed(c.g), encoder.displayed(c.b)});
  };
  struct Probe {
    PixelSamples samples;
    glm::vec3 key{0.0f};  // what neighbours compare: the colour, or its displayed L*a*b*
    bool traced = false;
  };
  const int x0 = std::max(0, rect.x - 1), y0 = std::max(0, rect.y - 1);
  const int x1 = std::min(frame_.width, rect.x + rect.width + 1), y1 = std::min(frame_.height, rect.y + rect.height + 1);
  const auto gridWidth = static_cast<std::size_t>(x1 - x0);
  std::vector<Probe> probes(gridWidth * static_cast<std::size_t>(y1 - y0));
  const auto probeAt = [&](int x, int y) -> const Probe& {
    Probe& p = probes[static_cast<std::size_t>(y - y0) * gridWidth + static_cast<std::size_t>(x - x0)];
    if (p.traced) return p;
    if (perceptual) {
      addCentreSample(x, y, p.samples, stats);
    } else {
      addSamples(x, y, 0, 1, p.samples, stats);
    }
    p.key = perceptual ? displayedLab(resolve(p.samples)) : resolve(p.samples);
    p.traced = true;
    return p;
  };
  const VisibleDifference visible(frame_.sampling.perceptualThreshold);
  const auto differ = [&](const glm::vec3& a, const glm::vec3& b) {
    if (perceptual) return visible(a, b);
    const glm::vec3 delta = glm::abs(a - b);
    const float t = frame_.sampling.adaptiveThreshold;
    return delta.r > t || delta.g > t || delta.b > t;
  };
  constexpr int kNeighbours[8][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
  const int neighbours = perceptual ? 8 : 4;
  std::size_t i = 0;
  for (int y = rect.y; y < rect.y + rect.height; ++y) {
    for (int x = rect.x; x < rect.x + rect.width; ++x, ++i) {
      if (!mask.empty() && !maskBit(mask, i)) continue;
      const Probe& probe = probeAt(x, y);
      bool differs = false;
      for (int k = 0; k < neighbours && !differs; ++k) {
        const int nx = x + kNeighbours[k][0], ny = y + kNeighbours[k][1];
        if (nx < 0 || ny < 0 || nx >= frame_.width || ny >= frame_.height) continue;
        differs = differ(probe.key, probeAt(nx, ny).key);
      }
      PixelSamples p = perceptual && differs ? PixelSamples{} : probe.samples;
      if (differs) addSamples(x, y, perceptual ? 0 : 1, frame_.sampling.samples, p, stats);
      out.push_back(resolve(p));
    }
  }
}

void Renderer::renderTileLinear(const TileRect& rect, std::span<const std::uint8_t> mask, std::vector<glm::vec3>& out,
                                RayStats& stats, const RowTraced& rowTraced) const {
  const std::size_t before = out.size();
  if (frame_.sampling.pattern == SamplePattern::kAdaptive || frame_.sampling.pattern == SamplePattern::kPerceptual) {
    renderAdaptive(rect, mask, out, stats);  // its pixels wait for their neighbours: told at once
    if (rowTraced) rowTraced(out.size() - before);
    return;
  }
  std::size_t i = 0;
  for (int y = rect.y; y < rect.y + rect.height; ++y) {
    const std::size_t rowStart = out.size();
    for (int x = rect.x; x < rect.x + rect.width; ++x, ++i) {
      if (!mask.empty() && !maskBit(mask, i)) continue;
      out.push_back(pixel(x, y, stats));
    }
    if (rowTraced && out.size() > rowStart) rowTraced(out.size() - rowStart);
  }
}

void Renderer::renderTile(const TileRect& rect, std::span<const std::uint8_t> mask, std::vector<std::uint8_t>& rgb,
                          RayStats& stats, const RowTraced& rowTraced) const {
  std::vector<glm::vec3> linear;
  linear.reserve(rect.pixelCount());
  renderTileLinear(rect, mask, linear, stats, rowTraced);
  const Encoder encoder(frame_.output);
  for (const glm::vec3& c : linear) {
    rgb.push_back(encoder.byte(c.r));
    rgb.push_back(encoder.byte(c.g));
    rgb.push_back(encoder.byte(c.b));
  }
}

}  // namespace glint
