#include "common/render/sampling.h"

#include <algorithm>
#include <cmath>

#include "common/math/float_bits.h"
#include "common/render/sobol.h"

namespace glint {
namespace {

// SplitMix64 finaliser (Steele, Lea and Flood 2014): a full-avalanche mix.
std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

int rowsFor(int samples) { return std::max(1, static_cast<int>(std::lround(std::sqrt(samples)))); }

// A value in [lo, hi) at fraction u in [0, 1): guards the rounding of
// lo + u (hi - lo) up to hi.
float lerpBelow(float lo, float hi, float u) {
  const float x = lo + u * (hi - lo);
  return x < hi ? x : std::nextafter(hi, lo);
}

// hashUniform in steps: the seed's, the pixel's, the sample's (which a
// sample's dimensions share), then each dimension's value from it.
std::uint64_t seedHash(std::uint32_t seed) { return mix(seed + 0x9e3779b97f4a7c15ULL); }

std::uint64_t pixelHash(std::uint64_t seedHash, int px, int py) {
  const std::uint64_t h = mix(seedHash ^ static_cast<std::uint32_t>(px));
  return mix(h ^ (static_cast<std::uint64_t>(static_cast<std::uint32_t>(py)) << 32));
}

std::uint64_t sampleHash(std::uint64_t pixelHash, int sample) {
  return mix(pixelHash ^ static_cast<std::uint32_t>(sample));
}

float dimensionUniform(std::uint64_t hash, int dimension) {
  const std::uint64_t h = mix(hash ^ (static_cast<std::uint64_t>(static_cast<std::uint32_t>(dimension)) << 32));
  // The top 24 bits are exact in a float and stay below 1.
  return static_cast<float>(h >> 40) * 0x1p-24f;
}

glm::vec2 stratifiedPoint(std::uint64_t pixelHash, int sample, int pair) {
  const std::uint64_t h = mix(pixelHash ^ (static_cast<std::uint64_t>(static_cast<std::uint32_t>(pair)) << 32));
  return scrambledSobol(static_cast<std::uint32_t>(sample), static_cast<std::uint32_t>(h >> 32));
}

}  // namespace

float hashUniform(std::uint32_t seed, int px, int py, int sample, int dimension) {
  return dimensionUniform(sampleHash(pixelHash(seedHash(seed), px, py), sample), dimension);
}

Stratum jitteredStratum(int samples, int sample) {
  const int rows = rowsFor(samples);
  const int base = samples / rows;
  const int extra = samples % rows;  // the first `extra` rows get one more cell
  // Find the row of this sample and the index of its first sample.
  int first = 0;
  int row = 0;
  int cells = base + (extra > 0 ? 1 : 0);
  while (sample >= first + cells) {
    first += cells;
    ++row;
    cells = base + (row < extra ? 1 : 0);
  }
  const int cell = sample - first;
  const auto n = static_cast<float>(samples);
  const auto k = static_cast<float>(cells);
  return {static_cast<float>(cell) / k, static_cast<float>(cell + 1) / k,
          static_cast<float>(first) / n, static_cast<float>(first + cells) / n};
}

SampleLayout::SampleLayout(const SamplingSettings& sampling)
    : seedHash_(seedHash(sampling.seed)), pattern_(sampling.pattern) {
  const int n = sampling.samples;
  if (pattern_ == SamplePattern::kSobol) return;
  if (pattern_ != SamplePattern::kRegular) {
    for (int sample = 0; sample < n; ++sample) strata_.push_back(jitteredStratum(n, sample));
    return;
  }
  if (n == 2) {
    points_ = {glm::vec2(0.25f), glm::vec2(0.75f)};
    return;
  }
  const int k = rowsFor(n);
  const auto kf = static_cast<float>(k);
  for (int sample = 0; sample < n; ++sample) {
    points_.push_back({(static_cast<float>(sample % k) + 0.5f) / kf, (static_cast<float>(sample / k) + 0.5f) / kf});
  }
}

glm::vec2 stratumPoint(const Stratum& s, const glm::vec2& u) {
  return {std::min(lerpBelow(s.x0, s.x1, u.x), kOneMinusEpsilon), std::min(lerpBelow(s.y0, s.y1, u.y), kOneMinusEpsilon)};
}

float SampleKey::uniform(int dimension) const { return dimensionUniform(hash, dimension); }

glm::vec2 SampleKey::stratified(int pair) const { return stratifiedPoint(pixel, sample, pair); }

SampleLayout::Pixel SampleLayout::pixel(int px, int py) const { return {pixelHash(seedHash_, px, py)}; }

SampleKey SampleLayout::key(const Pixel& pixel, int sample) {
  return {sampleHash(pixel.hash, sample), pixel.hash, sample};
}

glm::vec2 SampleLayout::position(const Pixel& pixel, int sample) const {
  const auto i = static_cast<std::size_t>(sample);
  if (pattern_ == SamplePattern::kSobol) return stratifiedPoint(pixel.hash, sample, SampleKey::kPixelPair);
  if (pattern_ == SamplePattern::kRegular) return points_[i];
  const std::uint64_t h = sampleHash(pixel.hash, sample);
  return stratumPoint(strata_[i], {dimensionUniform(h, 0), dimensionUniform(h, 1)});
}

}  // namespace glint
