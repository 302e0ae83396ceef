#pragma once

#include <cstdint>

namespace glint {

// Who draws a pixel of the hybrid frame, and how the tracer fills it when it
// is the tracer. The raster pass writes the first three per fragment (the
// surface attachment of client/raster/raster_target.h); raster_edges adds the last.
enum PixelMark : std::uint8_t {
  kRasterPixel = 0,      // OpenGL's shading stays
  kMaskedPixel = 1,      // the mask names its material: traced with the frame's settings
  kShadowEdgePixel = 2,  // the shadow maps cannot decide it: traced with direct light
  kRasterEdgePixel = 3,  // a geometric edge of surfaces OpenGL draws: traced with direct light (anti-aliasing)
};
constexpr unsigned kPixelMarkBits = 2;  // a surface value is object << kPixelMarkBits | mark
constexpr std::uint8_t markOf(std::uint32_t surface) {
  return static_cast<std::uint8_t>(surface & ((1u << kPixelMarkBits) - 1));
}

// Traced with direct light alone (max depth 1): the pixel's neighbours are
// OpenGL's, which draws no reflections.
constexpr bool tracedWithDirectLight(std::uint8_t mark) { return mark >= kShadowEdgePixel; }

}  // namespace glint
