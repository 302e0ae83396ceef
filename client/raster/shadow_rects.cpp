#include "client/raster/shadow_rects.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

namespace glint::gl {
namespace {

// Pixels a spot's projected box is widened by: interpolation and rounding
// of a fragment's position on the way to its pixel.
constexpr float kMarginPixels = 2.0f;

// Whether the eye sees the spot's plane from the side its light is not on.
bool seenFromBehind(const ShadowSpot& spot, const glm::vec3& eye) {
  if (spot.plane == glm::vec4(0.0f)) return false;
  const float height = glm::dot(glm::vec3(spot.plane), eye) - spot.plane.w;
  return height < -1e-4f * glm::length(eye - spot.corners[0]);
}

class CellGrid {
 public:
  CellGrid(int width, int height)
      : width_(width),
        height_(height),
        columns_((width + kShadowRectTile - 1) / kShadowRectTile),
        rows_((height + kShadowRectTile - 1) / kShadowRectTile),
        cells_(static_cast<std::size_t>(columns_ * rows_)) {}

  // Marks the cells a box in window coordinates touches.
  void mark(glm::vec2 min, glm::vec2 max) {
    const auto cell = [](float v, int count) {
      return static_cast<int>(
          std::clamp(std::floor(v / kShadowRectTile), 0.0f, static_cast<float>(count - 1)));
    };
    if (max.x < 0.0f || max.y < 0.0f || min.x > static_cast<float>(width_) ||
        min.y > static_cast<float>(height_))
      return;
    for (int y = cell(min.y, rows_); y <= cell(max.y, rows_); ++y) {
      for (int x = cell(min.x, columns_); x <= cell(max.x, columns_); ++x)
        cells_[static_cast<std::size_t>(y * columns_ + x)] = 1;
    }
  }

  std::vector<ScissorRect> rects() const {
    std::vector<ScissorRect> done, open;
    for (int y = 0; y < rows_; ++y) {
      std::vector<ScissorRect> row;
      for (int x = 0; x < columns_; ++x) {
        const bool on = cells_[static_cast<std::size_t>(y * columns_ + x)] != 0;
        if (row.empty() || row.back().shadows != on)
          row.push_back({x * kShadowRectTile, y * kShadowRectTile, 0, 0, on});
        row.back().width = std::min(width_, (x + 1) * kShadowRectTile) - row.back().x;
      }
      const int top = std::min(height_, (y + 1) * kShadowRectTile);
      const bool same =
          open.size() == row.size() && std::equal(row.begin(), row.end(), open.begin(),
                                                  [](const ScissorRect& a, const ScissorRect& b) {
                                                    return a.x == b.x && a.width == b.width &&
                                                           a.shadows == b.shadows;
                                                  });
      if (!same) {
        done.insert(done.end(), open.begin(), open.end());
        open = row;
      }
      for (ScissorRect& r : open) r.height = top - r.y;
    }
    done.insert(done.end(), open.begin(), open.end());
    return done;
  }

 private:
  int width_, height_, columns_, rows_;
  std::vector<char> cells_;
};

}  // namespace

WindowBox windowBox(std::span<const glm::vec3> points, const glm::mat4& viewProjection,
                    glm::vec2 size) {
  WindowBox box;
  for (const glm::vec3& p : points) {
    const glm::vec4 clip = viewProjection * glm::vec4(p, 1.0f);
    if (!(clip.w > 0.0f)) return {glm::vec2(-INFINITY), glm::vec2(INFINITY)};
    const glm::vec2 window = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * size;
    box.min = glm::min(box.min, window);
    box.max = glm::max(box.max, window);
  }
  return box;
}

ShadowLayout shadowLayout(const std::vector<ShadowSpot>& spots, const glm::mat4& viewProjection,
                          const glm::vec3& eye, int width, int height) {
  CellGrid grid(width, height);
  ShadowLayout layout;
  const glm::vec2 size(static_cast<float>(width), static_cast<float>(height));
  for (const ShadowSpot& spot : spots) {
    if (seenFromBehind(spot, eye)) continue;
    layout.spotted.push_back(spot.prim);
    const WindowBox box =
        windowBox(std::span(spot.corners).first(static_cast<std::size_t>(spot.cornerCount)),
                  viewProjection, size);
    grid.mark(box.min - kMarginPixels, box.max + kMarginPixels);
  }
  std::sort(layout.spotted.begin(), layout.spotted.end());
  layout.spotted.erase(std::unique(layout.spotted.begin(), layout.spotted.end()),
                       layout.spotted.end());
  if (!layout.spotted.empty()) layout.rects = grid.rects();
  return layout;
}

}  // namespace glint::gl
