#pragma once

#include <limits>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "common/ray.h"

namespace glint {

// Axis-aligned box. A default box is empty (min = +inf, max = -inf), so a
// union needs no special case for the first element.
struct Bounds3 {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  glm::vec3 extent() const { return max - min; }
  glm::vec3 centre() const { return 0.5f * (min + max); }
  float surfaceArea() const;
  int longestAxis() const;
  void expand(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void expand(const Bounds3& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
};

// Entry and exit distance of a ray through a box, clipped to [tMin, tMax].
struct SlabHit {
  float t0;
  float t1;
};

// Robust slab test (Williams et al. 2005, "An Efficient and Robust Ray-Box
// Intersection Algorithm"; Ize 2013, "Robust BVH Ray Traversal"). The far
// distance is scaled by 1 + 2 gamma(3) so rounding never culls a box the ray
// touches, and the comparisons are ordered so that a NaN (0 * inf, an origin
// exactly on a slab plane of an axis the ray is parallel to) never replaces
// the running interval: boundaries count as inside. Returns false on a miss;
// on a hit, t0 <= t1 and neither is NaN.
bool intersectSlabs(const Bounds3& b, const Ray& ray, float tMin, float tMax, SlabHit* hit);

}  // namespace glint
