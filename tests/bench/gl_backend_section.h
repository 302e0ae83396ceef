#pragma once

#include <string>

namespace glint::bench {

// The headless OpenGL backends side by side (EGL's surfaceless platform and
// OSMesa, those this build has): each one's context start-up and its GL
// pass (the hybrid frame's raster and readback, markHybrid) on the thesis's
// scenes and the bunny, frames alternating between the backends; medians,
// and whether the two drew the same bytes.
void glBackendSection(const std::string& scenes, bool quick);

}  // namespace glint::bench
