#pragma once

#include <vector>

#include "common/image/frame_image.h"

namespace glint {

// A frame's linear colour before 8-bit rounding. Row 0 at the top, RGB floats.
struct LinearImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;
};

// The per-channel mean of two images of one size (two half-sample
// references make one full one).
LinearImage average(const LinearImage& a, const LinearImage& b);

}  // namespace glint
