#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "common/image/frame_image.h"
#include "common/image/linear_image.h"

namespace glint {

// FLIP, the perceptual difference of two images flipped back and forth in
// front of a viewer: Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom,
// Fairchild, "FLIP: A Difference Evaluator for Alternating Images", HPG 2020.
// This is LDR-FLIP: linear RGB in [0, 1] (values outside are clamped), each
// pixel's error in [0, 1] from a colour term (the images filtered by the
// eye's contrast sensitivity in YCxCz, then the Hunt-adjusted HyAB distance
// in L*a*b*) raised to the power one minus a feature term (the difference of
// edges and points the two images show in luminance).

// The paper's viewing condition: 0.7 m from a 0.7 m wide, 3840-pixel display.
inline constexpr double kFlipPixelsPerDegree = 0.7 * (3840.0 / 0.7) * (3.14159265358979 / 180.0);

// A per-pixel error map, row 0 at the top.
struct FlipMap {
  int width = 0;
  int height = 0;
  std::vector<float> error;  // width * height values in [0, 1]
};

// Pooled values of a map: its mean, and the errors that 95 % and 99 % of the
// pixels stay at or below (nearest rank).
struct FlipStats {
  double mean = 0.0;
  double p95 = 0.0;
  double p99 = 0.0;
};

// The error of `test` against `reference` (linear RGB; InputError when their
// sizes differ) seen at `pixelsPerDegree`.
FlipMap flip(const LinearImage& reference, const LinearImage& test, double pixelsPerDegree = kFlipPixelsPerDegree);

// HDR-FLIP (Andersson, Nilsson, Shirley, Akenine-Moller, "Visualizing
// Errors in Rendered High Dynamic Range Images", Eurographics 2021 short
// papers): LDR-FLIP of both images exposed by 2^e and tone mapped by ACES
// (Narkowicz's fit) at exposures e from `start` to `stop`, `count` of them,
// each pixel's largest error. The range comes from the reference: at
// `start` its brightest pixel, at `stop` its median luminance, maps to the
// tone curve's 0.85; one exposure a stop apart, two at least.
struct HdrExposures {
  float start = 0.0f;
  float stop = 0.0f;
  int count = 0;
};

// The exposures for `reference`; none (count 0) when its median luminance
// is not positive, where the range is undefined.
HdrExposures hdrExposures(const LinearImage& reference);

// `exposures.count` must be 2 or more.
FlipMap hdrFlip(const LinearImage& reference, const LinearImage& test, const HdrExposures& exposures,
                double pixelsPerDegree = kFlipPixelsPerDegree);

FlipStats flipStats(const FlipMap& map);

// The map in the paper's colour map (magma: black 0, purple, orange, pale
// yellow 1), as the paper shows its errors.
FrameImage magmaImage(const FlipMap& map);

}  // namespace glint
