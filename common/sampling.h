#pragma once

#include <cstdint>

#include <glm/vec2.hpp>

#include "common/scene.h"

namespace glint {

// A uniform float in [0, 1) from a hash of (seed, pixel, sample, dimension):
// the same inputs always give the same value, so an image does not depend on
// the thread count, the tile split or the order pixels are visited in.
float hashUniform(std::uint32_t seed, int px, int py, int sample, int dimension);

// Position of sample `sample` of pixel (px, py) inside the pixel's unit
// square, in [0, 1)^2, before the filter warps it.
//  - regular: a k x k grid of cell centres (n = k^2); n = 2 is the two
//    diagonal quarter points (0.25, 0.25) and (0.75, 0.75).
//  - jittered: n equal-area strata, one sample each, uniformly placed in its
//    stratum. For any n: rows of floor or ceil(n / rows) cells whose heights
//    are proportional to their cell count, so every stratum has area 1 / n.
glm::vec2 samplePosition(const SamplingSettings& sampling, int px, int py, int sample);

// Whether a pattern accepts this sample count (regular: 1, 2, 4, 9, 16 ...).
bool validSampleCount(SamplePattern pattern, int samples);

// The stratum of a jittered sample: [x0, x1) x [y0, y1).
struct Stratum {
  float x0, x1, y0, y1;
};
Stratum jitteredStratum(int samples, int sample);

}  // namespace glint
