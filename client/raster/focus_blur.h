#pragma once

#include <cstdint>
#include <vector>

#include "common/scene/scene.h"

namespace glint {

// OpenGL draws through a pinhole; a thin lens (camera aperture > 0) blurs
// every point off the plane of focus over its circle of confusion. The
// pixels whose point's circle is wider than half a pixel are marked for
// tracing with the frame's settings (kMaskedPixel), and so is every pixel a
// blur may reach: within the frame's widest circle's radius of a marked one
// (a square, conservatively). `depth` is OpenGL's (near / the distance along
// the view axis; 0 for the background, infinitely far), `near` its near
// plane. Returns the pixels marked; marks other than OpenGL's own are kept.
std::size_t markOutOfFocus(const FrameSettings& frame, float near, const std::vector<float>& depth,
                           std::vector<std::uint8_t>& mask);

}  // namespace glint
