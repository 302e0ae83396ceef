#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "common/scene/scene.h"

namespace glint {

// A uniform float in [0, 1) from a hash of (seed, pixel, sample, dimension):
// the same inputs always give the same value, so an image does not depend on
// the thread count, the tile split or the order pixels are visited in.
float hashUniform(std::uint32_t seed, int px, int py, int sample, int dimension);

// The stratum of a jittered sample: [x0, x1) x [y0, y1).
struct Stratum {
  float x0, x1, y0, y1;
};
Stratum jitteredStratum(int samples, int sample);
// The point at fraction u (in [0, 1)^2) of a stratum, inside it.
glm::vec2 stratumPoint(const Stratum& s, const glm::vec2& u);

// The random choices of one camera sample past its place in the pixel (its
// point on the lens, its points on area lights, its glossy reflections'
// directions): uniform(d) is hashUniform's value of the sample for dimension
// d, so they too depend on the pixel and the sample alone.
struct SampleKey {
  // The dimensions' uses: 0 and 1 the place in the pixel, 2 and 3 the point
  // on the lens, from 4 the points on area lights and then the glossy lobes'
  // directions (their layout: Tracer::lightDimension and lobeDimension).
  static constexpr int kLensDimension = 2;
  static constexpr int kFirstLightDimension = 4;
  // stratified()'s pairs: the place in the pixel (the sobol pattern's),
  // then path transport's from kFirstPathPair.
  static constexpr int kPixelPair = 0;
  static constexpr int kFirstPathPair = 1;
  std::uint64_t hash = 0;   // of the seed, the pixel and the sample
  std::uint64_t pixel = 0;  // of the seed and the pixel, which its samples share
  int sample = 0;
  float uniform(int dimension) const;
  // The sample's point in a sequence over the pixel's samples, one for each
  // `pair` of dimensions: a scrambled Sobol sequence (sobol.h) whose
  // scramble comes from the pixel and the pair. A pixel's n samples then
  // cover the square evenly (one in each of n equal cells of any shape when
  // n is a power of two) where uniform()'s values fall independently.
  glm::vec2 stratified(int pair) const;
};

// Where a frame's samples lie: position(px, py, sample) is sample `sample`
// (0 to samples - 1) of pixel (px, py) inside the pixel's unit square, in
// [0, 1)^2, before the filter warps it.
//  - regular: a k x k grid of cell centres (n = k^2); n = 2 is the two
//    diagonal quarter points (0.25, 0.25) and (0.75, 0.75).
//  - jittered (and adaptive): n equal-area strata, one sample each,
//    uniformly placed in its stratum by hashUniform's dimensions 0 and 1.
//    For any n: rows of floor or ceil(n / rows) cells whose heights are
//    proportional to their cell count, so every stratum has area 1 / n.
//  - sobol: the sample's point of SampleKey::stratified's kPixelPair: at n
//    a power of two, one sample in each of n equal cells of every shape
//    (n x 1, n/2 x 2, ...), so an edge across the pixel, in any
//    direction, is found in proportion to the area it cuts.
// The points and strata, the same for every pixel, are computed once.
class SampleLayout {
 public:
  // What a pixel's samples share of their hash (hashUniform's seed and
  // pixel steps), computed once per pixel instead of once per sample.
  struct Pixel {
    std::uint64_t hash = 0;
  };

  explicit SampleLayout(const SamplingSettings& sampling);
  Pixel pixel(int px, int py) const;
  // Sample `sample` of the pixel (-1: the perceptual pattern's centre ray).
  static SampleKey key(const Pixel& pixel, int sample);
  glm::vec2 position(const Pixel& pixel, int sample) const;
  glm::vec2 position(int px, int py, int sample) const { return position(pixel(px, py), sample); }

 private:
  std::uint64_t seedHash_;  // the seed's step of the hash, the same for every pixel
  SamplePattern pattern_;
  std::vector<glm::vec2> points_;  // regular: each sample's point
  std::vector<Stratum> strata_;    // jittered: each sample's stratum
};

}  // namespace glint
