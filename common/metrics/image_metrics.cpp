#include "common/metrics/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/base/error.h"

namespace glint {

std::vector<float> pixelErrors(const LinearImage& image, const LinearImage& reference) {
  if (image.width != reference.width || image.height != reference.height) {
    throw InputError("images of different sizes cannot be compared (" + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " and " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height) + ")");
  }
  std::vector<float> errors(image.rgb.size() / 3);
  for (std::size_t p = 0; p < errors.size(); ++p) {
    float e = 0.0f;
    for (int k = 0; k < 3; ++k) e = std::max(e, std::abs(image.rgb[3 * p + k] - reference.rgb[3 * p + k]));
    errors[p] = e;
  }
  return errors;
}

ImageError compareImages(const LinearImage& image, const LinearImage& reference) {
  const std::vector<float> perPixel = pixelErrors(image, reference);
  ImageError e;
  double squares = 0.0;
  for (std::size_t i = 0; i < image.rgb.size(); ++i) {
    const double d = static_cast<double>(image.rgb[i]) - reference.rgb[i];
    squares += d * d;
  }
  const auto channels = static_cast<double>(std::max<std::size_t>(1, image.rgb.size()));
  e.rmse = std::sqrt(squares / channels);
  e.psnrDb = e.rmse > 0.0 ? 20.0 * std::log10(1.0 / e.rmse) : std::numeric_limits<double>::infinity();
  std::size_t over1 = 0, over8 = 0;
  for (const float p : perPixel) {
    e.maxError = std::max(e.maxError, static_cast<double>(p));
    over1 += p > 1.0f / 255.0f ? 1 : 0;
    over8 += p > 8.0f / 255.0f ? 1 : 0;
  }
  const auto pixels = static_cast<double>(std::max<std::size_t>(1, perPixel.size()));
  e.over1 = static_cast<double>(over1) / pixels;
  e.over8 = static_cast<double>(over8) / pixels;
  return e;
}

}  // namespace glint
