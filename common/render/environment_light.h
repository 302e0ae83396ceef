#pragma once

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/scene/environment.h"

namespace glint {

// The environment image as a light for path transport: directions drawn in
// proportion to its luminance. The image is cut into at most kMaxCells x
// kMaxCells / 2 cells of whole texels; a cell is drawn with a probability
// proportional to its brightest texel's luminance (so that every direction
// the bilinear lookup can light has a density above 0) times the sine of its
// polar angle (the solid angle its rows span), then a point uniformly in it.
class EnvironmentLight {
 public:
  static constexpr int kMaxCells = 256;

  explicit EnvironmentLight(const Environment& environment);

  // Whether the image is black: nothing to draw.
  bool empty() const { return total_ <= 0.0f; }

  struct Sample {
    glm::vec3 direction;  // unit, in the scene
    float pdf;            // per unit solid angle
  };
  // The direction at u in [0, 1)^2 (u.x picks the cell, u.y the point in it
  // along with u.x's remainder).
  Sample sample(const glm::vec2& u) const;
  // The density with which sample() draws the unit scene direction d.
  float pdf(const glm::vec3& d) const;

 private:
  float cellPdf(int cx, int cy) const;

  const Environment& environment_;
  int columns_, rows_;              // cells
  std::vector<float> weight_;       // per cell
  std::vector<float> cumulative_;   // cells summed in scan order, up to and including each
  float total_ = 0.0f;
};

}  // namespace glint
