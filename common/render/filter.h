#pragma once

#include <array>

#include "common/scene/scene.h"

namespace glint {

// A pixel reconstruction filter applied by warping samples (the thesis's
// tent filter "warps the samples toward the pixel centre"): a sample position
// u in [0, 1) per axis maps to an offset from the pixel centre distributed as
// |f|, and the sample carries weight sign(f(x) f(y)) (only the Mitchell
// filter has negative lobes). The filters are separable: f(x, y) = f(x) f(y).
//   box      radius 0.5  f = 1
//   tent     radius 1    f = 1 - |x|
//   gaussian radius 1.5  f = exp(-x^2 / (2 0.5^2)) - exp(-1.5^2 / (2 0.5^2))
//   mitchell radius 2    Mitchell-Netravali with B = C = 1/3
class Filter {
 public:
  explicit Filter(FilterType type);

  // Offset from the pixel centre, in pixels, for u in [0, 1).
  float warp(float u) const;
  // sign(f(offset)) for a warped offset: +1 or -1.
  float sign(float offset) const;
  float radius() const { return radius_; }
  float evaluate(float x) const;

 private:
  static constexpr int kTableSize = 1024;
  FilterType type_;
  float radius_;
  // Inverse CDF of |f| over [-radius, radius] for the tabulated filters.
  std::array<float, kTableSize + 1> cdf_{};
};

}  // namespace glint
