#include "common/optics.h"

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "common/float_bits.h"

namespace glint {

glm::vec3 reflect(const glm::vec3& d, const glm::vec3& n) {
  return glm::normalize(d - 2.0f * glm::dot(d, n) * n);
}

std::optional<glm::vec3> refract(const glm::vec3& d, const glm::vec3& n, float eta) {
  const float cosI = -glm::dot(d, n);
  const float sin2T = eta * eta * std::max(0.0f, 1.0f - cosI * cosI);
  if (sin2T >= 1.0f) return std::nullopt;
  const float cosT = std::sqrt(1.0f - sin2T);
  return glm::normalize(eta * d + (eta * cosI - cosT) * n);
}

glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& n) {
  constexpr float kOrigin = 1.0f / 32.0f;
  constexpr float kFloatScale = 1.0f / 65536.0f;
  constexpr float kIntScale = 256.0f;
  glm::vec3 out;
  for (int i = 0; i < 3; ++i) {
    const auto ofs = static_cast<std::int32_t>(kIntScale * n[i]);
    const auto bits = static_cast<std::int32_t>(floatToBits(p[i]));
    const float moved = bitsToFloat(static_cast<std::uint32_t>(p[i] < 0.0f ? bits - ofs : bits + ofs));
    out[i] = std::abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : moved;
  }
  return out;
}

}  // namespace glint
