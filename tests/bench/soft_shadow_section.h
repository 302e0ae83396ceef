#pragma once

#include <string>

namespace glint::bench {

// Soft shadows of an area light (scenes/soft-shadows.json) and of a sphere
// light (scenes/sphere-light.json): the hybrid frame,
// which traces only the pixels not proved to see the light whole, beside the
// full trace at the same settings, for several light sample counts: shadow
// rays, median frame time and mean FLIP against a reference of 1,024 light
// samples a pixel (16 jittered samples of 64 points each), with the hybrid's
// ratios to the full trace's.
void softShadowSection(const std::string& scenes, bool quick);

}  // namespace glint::bench
