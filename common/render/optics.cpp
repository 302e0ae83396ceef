#include "common/render/optics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "common/math/float_bits.h"

namespace glint {

glm::vec3 reflect(const glm::vec3& d, const glm::vec3& n) {
  return glm::normalize(d - 2.0f * glm::dot(d, n) * n);
}

glm::vec3 mirrorDirection(const glm::vec3& d, const glm::vec3& ns, const glm::vec3& ng) {
  const glm::vec3 r = reflect(d, ns);
  return glm::dot(r, ng) <= 0.0f ? reflect(d, ng) : r;
}

float fresnelDielectric(float cosIn, float eta) {
  const float sin2T = eta * eta * std::max(0.0f, 1.0f - cosIn * cosIn);
  if (sin2T >= 1.0f) return 1.0f;
  const float cosT = std::sqrt(1.0f - sin2T);
  const float s = (eta * cosIn - cosT) / (eta * cosIn + cosT);
  const float p = (cosIn - eta * cosT) / (cosIn + eta * cosT);
  return 0.5f * (s * s + p * p);
}

std::optional<glm::vec3> refract(const glm::vec3& d, const glm::vec3& n, float eta) {
  // In double: near the critical angle cos^2 T = 1 - eta^2 (1 - cos^2 I)
  // cancels almost completely, and float would lose most of its digits.
  const glm::dvec3 dd(d), nd(n);
  const double e = eta;
  const double cosI = -glm::dot(dd, nd);
  const double cos2T = 1.0 - e * e * std::max(0.0, 1.0 - cosI * cosI);
  if (cos2T <= 0.0) return std::nullopt;
  return glm::vec3(glm::normalize(e * dd + (e * cosI - std::sqrt(cos2T)) * nd));
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

glm::vec3 offsetRayOrigin(const glm::vec3& p, float error, const glm::vec3& n) {
  const float distance = error * (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
  return offsetRayOrigin(p + distance * n, n);
}

}  // namespace glint
