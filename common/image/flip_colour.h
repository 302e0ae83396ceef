#pragma once

#include <glm/vec3.hpp>

namespace glint {

// FLIP's colour space and colour term (Andersson et al., "FLIP: A
// Difference Evaluator for Alternating Images", HPG 2020), shared by the
// perceptual sample pattern and the raster's colour edges (a pixel's colour
// against its neighbours') and the FLIP image metric (common/metrics/flip.h).
// The powers are power()'s (common/math/power.h): the perceptual pattern
// decides pixels by VisibleDifference, and a pixel must not depend on the
// machine's libm.

// FLIP's colour term for two flat colours, without the spatial filtering
// (which only lowers the difference of small features): what a pixel's
// error would be at most, were it as wide as the eye resolves. flipLab is
// the Hunt-adjusted L*a*b* of a displayed linear colour; VisibleDifference
// asks whether the HyAB distance of two such colours, compressed and mapped
// to [0, 1] as the map's colour term is, exceeds a threshold, by comparing
// the distance with the one the threshold maps to (the term grows with the
// distance): one power for the threshold, none a pair.
glm::vec3 flipLab(const glm::vec3& displayedLinear);

class VisibleDifference {
 public:
  explicit VisibleDifference(float threshold);
  bool operator()(const glm::vec3& labA, const glm::vec3& labB) const;

 private:
  float distance_;
};

// The steps of the colour space, for the metric.
namespace flip_colour {

// The paper's colour parameters: the exponent, and the share of the colour
// range mapped to [0, kBelowCut].
inline constexpr float kColourExponent = 0.7f;
inline constexpr float kCutShare = 0.4f;
inline constexpr float kBelowCut = 0.95f;

glm::vec3 linearToXyz(const glm::vec3& c);
glm::vec3 xyzToLinear(const glm::vec3& c);
// YCxCz: L*a*b* without the cube root (linear in XYZ, so it may be filtered).
glm::vec3 xyzToYcxcz(glm::vec3 c);
glm::vec3 ycxczToXyz(const glm::vec3& c);
glm::vec3 xyzToLab(glm::vec3 c);
// The Hunt effect: chroma weighs less in the dark.
glm::vec3 hunt(const glm::vec3& lab);
// HyAB: city-block in lightness, Euclidean in the chroma plane.
float hyab(const glm::vec3& a, const glm::vec3& b);
// The largest colour difference, green against blue, raised to
// kColourExponent (worked out once).
float largestColourDifference();
// A HyAB distance compressed and mapped to [0, 1]: distances up to kCutShare
// of the largest to [0, kBelowCut], the rest to (kBelowCut, 1].
float colourError(float distance);

}  // namespace flip_colour
}  // namespace glint
