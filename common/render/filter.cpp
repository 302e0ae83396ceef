#include "common/render/filter.h"

#include <algorithm>
#include <cmath>

#include "common/math/power.h"

namespace glint {
namespace {

float mitchell(float x) {
  constexpr float b = 1.0f / 3.0f;
  constexpr float c = 1.0f / 3.0f;
  x = std::abs(x);
  if (x <= 1.0f) {
    return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) / 6;
  }
  if (x <= 2.0f) {
    return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x +
            (8 * b + 24 * c)) /
           6;
  }
  return 0.0f;
}

float radiusOf(FilterType type) {
  switch (type) {
    case FilterType::kBox:
      return 0.5f;
    case FilterType::kTent:
      return 1.0f;
    case FilterType::kGaussian:
      return 1.5f;
    case FilterType::kMitchell:
      return 2.0f;
  }
  return 0.5f;
}

}  // namespace

Filter::Filter(FilterType type) : type_(type), radius_(radiusOf(type)) {
  if (type_ != FilterType::kGaussian && type_ != FilterType::kMitchell) return;
  // Tabulate the CDF of |f| on kTableSize cells (midpoint rule).
  double sum = 0.0;
  cdf_[0] = 0.0f;
  std::array<double, kTableSize + 1> acc{};
  for (int i = 0; i < kTableSize; ++i) {
    const float x = -radius_ + 2.0f * radius_ * (static_cast<float>(i) + 0.5f) / kTableSize;
    sum += std::abs(evaluate(x));
    acc[i + 1] = sum;
  }
  for (int i = 0; i <= kTableSize; ++i) cdf_[i] = static_cast<float>(acc[i] / sum);
  cdf_[kTableSize] = 1.0f;
}

float Filter::evaluate(float x) const {
  switch (type_) {
    case FilterType::kBox:
      return std::abs(x) <= 0.5f ? 1.0f : 0.0f;
    case FilterType::kTent:
      return std::max(0.0f, 1.0f - std::abs(x));
    case FilterType::kGaussian: {
      constexpr float kInvTwoSigma2 = 1.0f / (2.0f * 0.5f * 0.5f);
      return std::max(0.0f, exponential(-x * x * kInvTwoSigma2) -
                                exponential(-radius_ * radius_ * kInvTwoSigma2));
    }
    case FilterType::kMitchell:
      return mitchell(x);
  }
  return 0.0f;
}

float Filter::warp(float u) const {
  switch (type_) {
    case FilterType::kBox:
      return u - 0.5f;
    case FilterType::kTent:
      // Inverse CDF of the tent on [-1, 1].
      return u < 0.5f ? -1.0f + std::sqrt(2.0f * u) : 1.0f - std::sqrt(2.0f - 2.0f * u);
    case FilterType::kGaussian:
    case FilterType::kMitchell:
      if (u == 0.5f) return 0.0f;  // exactly the centre, as for box and tent
      break;
  }
  // Invert the tabulated CDF: find the cell, interpolate linearly inside it.
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  const int cell = std::clamp(static_cast<int>(it - cdf_.begin()) - 1, 0, kTableSize - 1);
  const float lo = cdf_[cell];
  const float hi = cdf_[cell + 1];
  const float t = hi > lo ? (u - lo) / (hi - lo) : 0.5f;
  return -radius_ + 2.0f * radius_ * (static_cast<float>(cell) + t) / kTableSize;
}

float Filter::sign(float offset) const {
  if (type_ != FilterType::kMitchell) return 1.0f;  // the only filter with negative lobes
  return evaluate(offset) < 0.0f ? -1.0f : 1.0f;
}

}  // namespace glint
