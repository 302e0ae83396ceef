#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace glint {

// The raster's anti-aliasing is the tracer's: OpenGL draws one sample a
// pixel, and the pixels on a geometric edge of the surfaces it draws are
// traced with the frame's samples (NVIDIA's adaptive temporal anti-aliasing
// traces a rasterizer's edges the same way). Two neighbouring pixels (left
// and right, or above and below) straddle an edge when they show different
// objects (the background among them), or one object whose depth jumps or
// bends between them: each pixel's depth, extrapolated linearly from it and
// its other neighbour on that line, misses the other pixel's by more than
// kEdgeDepthTolerance of its depth, seen from both sides (a plane
// extrapolates exactly; an occluding contour or a sharp crease between the
// two does not). Requiring both sides keeps the pixels one further from the
// edge out (their extrapolation crosses it from one side only): tracing
// them too marked many more pixels of the thesis's scenes for no change in
// their error (docs/hybrid.md).
//
// `surface` holds the raster's `object << kPixelMarkBits | mark` per pixel
// and `depth` its depth (proportional to the distance along the view axis,
// or to its reciprocal, which OpenGL's depth is and which is linear across a
// plane's pixels; the test is relative, so either serves), rows from the top. Writes each pixel's PixelMark into `marks`: the raster's own, and
// for a pixel OpenGL drew that straddles an edge, kRasterEdgePixel, or
// kMaskedPixel where the pixel across the edge is masked (its samples that
// fall on the masked object then get that object's reflections, as the
// masked pixels do). Returns the pixels so marked.
constexpr float kEdgeDepthTolerance = 2e-3f;
std::size_t markRasterEdges(std::span<const std::uint32_t> surface, std::span<const float> depth, int width,
                            int height, std::span<std::uint8_t> marks);

}  // namespace glint
