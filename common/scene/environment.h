#pragma once

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/math/circular.h"

namespace glint {

// An environment image: the light that rays escaping the scene see, from
// every direction, in place of the flat background. Equirectangular, row 0
// at the top: a direction d (y up) is at
//   u = 1/2 + atan2(d.x, -d.z) / 2 pi,  v = acos(d.y / |d|) / pi,
// so the image's centre column lies along -z, u grows toward +x, the top
// row is straight up and the bottom row straight down. Texels are read
// bilinearly between their centres, wrapping around in u and clamped at
// the poles in v. A rotation turns the image about +y (right-handed: by 90
// degrees, what lay along +z lies along +x).
struct Environment {
  // The brightest radiance a texel keeps: sums of a few weighted lookups
  // stay finite in float.
  static constexpr float kMaxRadiance = 1e30f;

  int width = 0;
  int height = 0;
  std::vector<float> rgb;  // width * height * 3, linear; scaled by 2^exposure

  // The image's linear values times `scale`, each value that is negative or
  // not finite as 0 and none above kMaxRadiance, turned by `rotation`
  // radians about +y.
  Environment(int width, int height, std::vector<float> linear, float scale, float rotation = 0.0f);

  // The radiance seen along `direction` (any length but 0); black for a
  // direction that is 0 or not finite.
  glm::vec3 radiance(const glm::vec3& direction) const;

  glm::vec3 texel(int x, int y) const;

  // Where a direction (finite, largest component about 1) lies on the
  // image, u and v in [0, 1]; and the unit direction at (u, v), its inverse.
  glm::vec2 uvOf(const glm::vec3& d) const;
  glm::vec3 directionAt(const glm::vec2& uv) const;

 private:
  glm::vec3 bilinear(const glm::vec2& uv) const;

  SineCosine turn_;
};

}  // namespace glint
