#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "client/raster/light_proof.h"

namespace glint::gl {

// A rectangle of the frame in GL window coordinates (origin at the bottom
// left), and whether what is drawn in it reads the shadow maps.
struct ScissorRect {
  int x = 0, y = 0, width = 0, height = 0;
  bool shadows = false;
};

// A box in GL window coordinates.
struct WindowBox {
  glm::vec2 min{INFINITY}, max{-INFINITY};
  bool overlaps(const ScissorRect& r) const {
    return max.x >= r.x && min.x <= r.x + r.width && max.y >= r.y && min.y <= r.y + r.height;
  }
};
// The window box of `points` seen through viewProjection in a frame of
// `size` pixels; the whole frame (and beyond) when one lies behind the eye.
WindowBox windowBox(std::span<const glm::vec3> points, const glm::mat4& viewProjection,
                    glm::vec2 size);

// Where a batch reads the shadow maps this frame. A spot counts unless the
// eye sees its plane from the side away from its light (no light reaches
// that side); `spotted` lists the primitives (ShadowSpot::prim) with a spot
// that counts, ascending, each once. The frame is cut into cells of
// kShadowRectTile pixels; `rects` covers it, few rectangles (runs of equal
// cells along a row, merged with the row below where they match), those
// holding a counted spot's window box reading the maps. A spot reaching
// behind the eye covers the frame.
constexpr int kShadowRectTile = 32;
struct ShadowLayout {
  std::vector<std::uint32_t> spotted;
  std::vector<ScissorRect> rects;
};
ShadowLayout shadowLayout(const std::vector<ShadowSpot>& spots, const glm::mat4& viewProjection,
                          const glm::vec3& eye, int width, int height);

}  // namespace glint::gl
