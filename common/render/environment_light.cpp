#include "common/render/environment_light.h"

#include <algorithm>
#include <cmath>

#include "common/math/circular.h"

namespace glint {
namespace {

constexpr float kPi = 3.14159265358979f;

float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

}  // namespace

EnvironmentLight::EnvironmentLight(const Environment& environment)
    : environment_(environment),
      columns_(std::min(environment.width, kMaxCells)),
      rows_(std::min(environment.height, kMaxCells / 2)) {
  weight_.assign(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_), 0.0f);
  for (int y = 0; y < environment.height; ++y) {
    const int cy = static_cast<int>(static_cast<long long>(y) * rows_ / environment.height);
    for (int x = 0; x < environment.width; ++x) {
      const int cx = static_cast<int>(static_cast<long long>(x) * columns_ / environment.width);
      float& w = weight_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(cx)];
      w = std::max(w, luminance(environment.texel(x, y)));
    }
  }
  for (int cy = 0; cy < rows_; ++cy) {
    const float sine = sineCosine((static_cast<float>(cy) + 0.5f) / static_cast<float>(rows_) * kPi).sin;
    for (int cx = 0; cx < columns_; ++cx) {
      float& w = weight_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(cx)];
      w *= sine;
      total_ += w;
      cumulative_.push_back(total_);
    }
  }
}

float EnvironmentLight::cellPdf(int cx, int cy) const {
  // Per unit area of the (u, v) square: the cell's share over its area.
  const float w = weight_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(cx)];
  return w / total_ * static_cast<float>(columns_) * static_cast<float>(rows_);
}

EnvironmentLight::Sample EnvironmentLight::sample(const glm::vec2& u) const {
  const float target = u.x * total_;
  const auto at = std::upper_bound(cumulative_.begin(), cumulative_.end(), target);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(at - cumulative_.begin()), cumulative_.size() - 1);
  // u.x's place inside the cell's span of the cumulative sum: a second number.
  const float before = i > 0 ? cumulative_[i - 1] : 0.0f;
  const float span = cumulative_[i] - before;
  const float along = span > 0.0f ? std::clamp((target - before) / span, 0.0f, 0.99999994f) : 0.5f;
  const int cx = static_cast<int>(i % static_cast<std::size_t>(columns_));
  const int cy = static_cast<int>(i / static_cast<std::size_t>(columns_));
  const glm::vec2 uv{(static_cast<float>(cx) + along) / static_cast<float>(columns_),
                     (static_cast<float>(cy) + u.y) / static_cast<float>(rows_)};
  const float sine = sineCosine(uv.y * kPi).sin;
  const float pdf = sine > 0.0f ? cellPdf(cx, cy) / (2.0f * kPi * kPi * sine) : 0.0f;
  return {environment_.directionAt(uv), pdf};
}

float EnvironmentLight::pdf(const glm::vec3& d) const {
  const glm::vec2 uv = environment_.uvOf(d);
  const int cx = std::min(static_cast<int>(uv.x * static_cast<float>(columns_)), columns_ - 1);
  const int cy = std::min(static_cast<int>(uv.y * static_cast<float>(rows_)), rows_ - 1);
  const float sine = sineCosine(uv.y * kPi).sin;
  return sine > 0.0f ? cellPdf(cx, cy) / (2.0f * kPi * kPi * sine) : 0.0f;
}

}  // namespace glint
