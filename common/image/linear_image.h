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

// An 8-bit frame as linear values (byte / 255): the hybrid frame's raster
// pixels exist only as bytes.
LinearImage fromBytes(const FrameImage& image);

// The 8-bit frame a PNG holds: each value rounded as the tracer's tiles are.
FrameImage toBytes(const LinearImage& image);

// The per-channel mean of two images of one size (two half-sample
// references make one full one).
LinearImage average(const LinearImage& a, const LinearImage& b);

}  // namespace glint
