#include "common/scene/environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "common/math/finite.h"

namespace glint {
namespace {

// Where a unit direction lies on the image, u and v in [0, 1].
glm::vec2 equirectangularUv(const glm::vec3& d) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const float u = 0.5f + std::atan2(d.x, -d.z) / (2.0f * kPi);
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
  return {std::clamp(u, 0.0f, 1.0f), std::clamp(v, 0.0f, 1.0f)};
}

}  // namespace

Environment::Environment(int w, int h, std::vector<float> linear, float scale, float rotation)
    : width(w), height(h), rgb(std::move(linear)), turn_(sineCosine(rotation)) {
  if (w <= 0 || h <= 0 || rgb.size() != static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3) {
    throw std::invalid_argument("Environment: width * height * 3 values");
  }
  for (float& v : rgb) v = std::isfinite(v) && v > 0.0f ? std::min(v * scale, kMaxRadiance) : 0.0f;
}

glm::vec3 Environment::texel(int x, int y) const {
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
  return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

glm::vec3 Environment::radiance(const glm::vec3& direction) const {
  // Scaled to a largest component of 1 before it is normalised: the
  // length of a tiny or huge direction neither underflows nor overflows.
  const float largest = std::max({std::abs(direction.x), std::abs(direction.y), std::abs(direction.z)});
  if (!allFinite(direction) || !(largest > 0.0f)) return glm::vec3(0.0f);
  return bilinear(uvOf(direction / largest));
}

glm::vec2 Environment::uvOf(const glm::vec3& d) const {
  // Turned back by the rotation: where the direction lies on the image.
  const glm::vec3 onImage{d.x * turn_.cos - d.z * turn_.sin, d.y, d.x * turn_.sin + d.z * turn_.cos};
  return equirectangularUv(glm::normalize(onImage));
}

glm::vec3 Environment::directionAt(const glm::vec2& uv) const {
  constexpr float kPi = std::numbers::pi_v<float>;
  const SineCosine theta = sineCosine(uv.y * kPi);
  const SineCosine phi = sineCosine((uv.x - 0.5f) * 2.0f * kPi);
  const glm::vec3 onImage{theta.sin * phi.sin, theta.cos, -theta.sin * phi.cos};
  return {onImage.x * turn_.cos + onImage.z * turn_.sin, onImage.y, -onImage.x * turn_.sin + onImage.z * turn_.cos};
}

glm::vec3 Environment::bilinear(const glm::vec2& uv) const {
  // Texel centres at (i + 1/2) / size: x wraps around, y stops at the poles.
  const float x = uv.x * static_cast<float>(width) - 0.5f;
  const float y = std::clamp(uv.y * static_cast<float>(height) - 0.5f, 0.0f, static_cast<float>(height - 1));
  const float x0 = std::floor(x);
  const float y0 = std::floor(y);
  const float fx = x - x0;
  const float fy = y - y0;
  const int ix0 = (static_cast<int>(x0) % width + width) % width;
  const int ix1 = (ix0 + 1) % width;
  const int iy0 = static_cast<int>(y0);
  const int iy1 = std::min(iy0 + 1, height - 1);
  const glm::vec3 top = texel(ix0, iy0) * (1.0f - fx) + texel(ix1, iy0) * fx;
  const glm::vec3 bottom = texel(ix0, iy1) * (1.0f - fx) + texel(ix1, iy1) * fx;
  return top * (1.0f - fy) + bottom * fy;
}

}  // namespace glint
