#include "common/sampling.h"

#include <algorithm>
#include <cmath>

#include "common/float_bits.h"

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

}  // namespace

float hashUniform(std::uint32_t seed, int px, int py, int sample, int dimension) {
  std::uint64_t h = mix(seed + 0x9e3779b97f4a7c15ULL);
  h = mix(h ^ static_cast<std::uint32_t>(px));
  h = mix(h ^ (static_cast<std::uint64_t>(static_cast<std::uint32_t>(py)) << 32));
  h = mix(h ^ static_cast<std::uint32_t>(sample));
  h = mix(h ^ (static_cast<std::uint64_t>(static_cast<std::uint32_t>(dimension)) << 32));
  // The top 24 bits are exact in a float and stay below 1.
  return static_cast<float>(h >> 40) * 0x1p-24f;
}

bool validSampleCount(SamplePattern pattern, int samples) {
  if (samples < 1) return false;
  if (pattern != SamplePattern::kRegular || samples == 2) return true;
  const int k = static_cast<int>(std::lround(std::sqrt(samples)));
  return k * k == samples;
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

glm::vec2 samplePosition(const SamplingSettings& sampling, int px, int py, int sample) {
  const int n = sampling.samples;
  if (sampling.pattern == SamplePattern::kRegular) {
    if (n == 2) return sample == 0 ? glm::vec2(0.25f) : glm::vec2(0.75f);
    const int k = std::max(1, static_cast<int>(std::lround(std::sqrt(n))));
    const auto kf = static_cast<float>(k);
    return {(static_cast<float>(sample % k) + 0.5f) / kf, (static_cast<float>(sample / k) + 0.5f) / kf};
  }
  const Stratum s = jitteredStratum(n, sample);
  const float u = hashUniform(sampling.seed, px, py, sample, 0);
  const float v = hashUniform(sampling.seed, px, py, sample, 1);
  return {std::min(lerpBelow(s.x0, s.x1, u), kOneMinusEpsilon),
          std::min(lerpBelow(s.y0, s.y1, v), kOneMinusEpsilon)};
}

}  // namespace glint
