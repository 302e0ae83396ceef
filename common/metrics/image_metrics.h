#pragma once

#include "common/image/linear_image.h"

namespace glint {

// How far an image is from a reference, over every channel of every pixel
// (linear values in [0, 1]).
struct ImageError {
  double rmse = 0.0;
  double psnrDb = 0.0;    // 20 log10(1 / rmse); infinite for identical images
  double maxError = 0.0;  // the largest channel difference
  double over1 = 0.0;     // share of pixels with a channel off by more than 1/255
  double over8 = 0.0;     // ... by more than 8/255: visible
};

// Throws InputError when the sizes differ.
ImageError compareImages(const LinearImage& image, const LinearImage& reference);

// Per pixel, the largest channel difference: where the error is.
std::vector<float> pixelErrors(const LinearImage& image, const LinearImage& reference);

}  // namespace glint
