#include "common/image/flip_colour.h"

#include <cmath>

#include <glm/common.hpp>

#include "common/math/power.h"

namespace glint {
namespace flip_colour {
namespace {

// D65 white in XYZ, and its inverse.
constexpr glm::vec3 kWhite{0.950428545f, 1.0f, 1.088900371f};
constexpr glm::vec3 kInvWhite{1.052156925f, 1.0f, 0.918357670f};

}  // namespace

glm::vec3 linearToXyz(const glm::vec3& c) {
  return {(10135552.0f / 24577794.0f) * c.x + (8788810.0f / 24577794.0f) * c.y + (4435075.0f / 24577794.0f) * c.z,
          (2613072.0f / 12288897.0f) * c.x + (8788810.0f / 12288897.0f) * c.y + (887015.0f / 12288897.0f) * c.z,
          (1425312.0f / 73733382.0f) * c.x + (8788810.0f / 73733382.0f) * c.y + (70074185.0f / 73733382.0f) * c.z};
}

glm::vec3 xyzToLinear(const glm::vec3& c) {
  return {3.241003275f * c.x - 1.537398934f * c.y - 0.498615861f * c.z,
          -0.969224334f * c.x + 1.875930071f * c.y + 0.041554224f * c.z,
          0.055639423f * c.x - 0.204011202f * c.y + 1.057148933f * c.z};
}

glm::vec3 xyzToYcxcz(glm::vec3 c) {
  c *= kInvWhite;
  return {116.0f * c.y - 16.0f, 500.0f * (c.x - c.y), 200.0f * (c.y - c.z)};
}

glm::vec3 ycxczToXyz(const glm::vec3& c) {
  const float y = (c.x + 16.0f) / 116.0f;
  return glm::vec3(y + c.y / 500.0f, y, y - c.z / 200.0f) * kWhite;
}

glm::vec3 xyzToLab(glm::vec3 c) {
  constexpr float delta = 6.0f / 29.0f;
  const auto f = [](float t) {
    return t > delta * delta * delta ? cubeRoot(t) : t / (3.0f * delta * delta) + 4.0f / 29.0f;
  };
  c *= kInvWhite;
  const glm::vec3 t{f(c.x), f(c.y), f(c.z)};
  return {116.0f * t.y - 16.0f, 500.0f * (t.x - t.y), 200.0f * (t.y - t.z)};
}

glm::vec3 hunt(const glm::vec3& lab) {
  return {lab.x, 0.01f * lab.x * lab.y, 0.01f * lab.x * lab.z};
}

float hyab(const glm::vec3& a, const glm::vec3& b) {
  const float da = a.y - b.y, db = a.z - b.z;
  return std::abs(a.x - b.x) + std::sqrt(da * da + db * db);
}

float largestColourDifference() {
  static const float cmax = [] {
    const auto huntLab = [](const glm::vec3& rgb) { return hunt(xyzToLab(linearToXyz(rgb))); };
    return power(hyab(huntLab({0.0f, 1.0f, 0.0f}), huntLab({0.0f, 0.0f, 1.0f})), kColourExponent);
  }();
  return cmax;
}

float colourError(float distance) {
  const float cmax = largestColourDifference(), d = power(distance, kColourExponent), cut = kCutShare * cmax;
  return d < cut ? d * kBelowCut / cut : kBelowCut + (d - cut) / (cmax - cut) * (1.0f - kBelowCut);
}

}  // namespace flip_colour

using namespace flip_colour;

glm::vec3 flipLab(const glm::vec3& displayedLinear) {
  return hunt(xyzToLab(linearToXyz(glm::clamp(displayedLinear, 0.0f, 1.0f))));
}

VisibleDifference::VisibleDifference(float threshold) {
  // colourError's inverse: the distance whose compressed value is the threshold.
  const float cmax = largestColourDifference(), cut = kCutShare * cmax;
  const float compressed = threshold < kBelowCut ? threshold * cut / kBelowCut
                                                 : cut + (threshold - kBelowCut) / (1.0f - kBelowCut) * (cmax - cut);
  distance_ = power(compressed, 1.0f / kColourExponent);
}

bool VisibleDifference::operator()(const glm::vec3& labA, const glm::vec3& labB) const {
  return hyab(labA, labB) > distance_;
}

}  // namespace glint
