#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace glint {

// The perceptual mask rule's anti-aliasing: OpenGL's one sample a pixel
// aliases wherever its colours change, at a texture's edges and the maps'
// shadow edges as much as at geometric ones, and the aliasing shows only
// where the change does. Two neighbouring pixels (left and right, or above
// and below) that OpenGL shades (neither mark is kMaskedPixel) and whose
// colours as displayed (the 8-bit values through sRGB) differ by FLIP's
// colour term above `threshold` are both marked kRasterEdgePixel (traced
// with direct light and the frame's samples), unless traced already.
// `rgb` is the whole frame's raster colour, rows from the top; `marks` the
// frame's PixelMarks. Returns the pixels so marked.
std::size_t markColourEdges(std::span<const std::uint8_t> rgb, int width, int height, float threshold,
                            std::span<std::uint8_t> marks);

}  // namespace glint
