#pragma once

#include <cstdint>
#include <vector>

#include "client/raster/gl_api.h"
#include "common/render/tile.h"

namespace glint::gl {

// The framebuffer the raster pass draws into, one sample a pixel:
// - colour (RGBA8): GL's shading of the pixel;
// - surface (R32UI): what the pixel shows, `object << 2 | mark` (object 0 is
//   the background, objects count from 1; mark a PixelMark of the fragment);
// - depth (32-bit float): near / the distance along the view axis (reversed,
//   0 where nothing was drawn; RasterScene::Projection).
// Reads give rows from the top, as Glint's images are.
class RasterTarget {
 public:
  explicit RasterTarget(const Api& gl) : gl_(gl) {}
  ~RasterTarget();
  RasterTarget(const RasterTarget&) = delete;
  RasterTarget& operator=(const RasterTarget&) = delete;

  // Binds a target of this size (made anew when the size changes) with both
  // colour attachments drawn; throws InputError when GL cannot make it.
  void bind(int width, int height);
  // Clears colour to `background` (exact 8-bit values), surface to
  // `backgroundSurface` (object 0 and its mark: client/raster/pixel_mark.h) and
  // depth to 0 (infinitely far).
  void clear(const std::uint8_t background[3], std::uint32_t backgroundSurface);
  void readColour(const TileRect& window, std::vector<std::uint8_t>& rgb) const;
  void readSurface(std::vector<std::uint32_t>& surface) const;
  void readDepth(std::vector<float>& depth) const;

 private:
  void release();
  const Api& gl_;
  unsigned framebuffer_ = 0;
  unsigned buffers_[3] = {};  // colour, surface, depth
  int width_ = 0;
  int height_ = 0;
};

}  // namespace glint::gl
