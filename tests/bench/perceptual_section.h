#pragma once

#include <string>

namespace glint::bench {

// The mask rules auto and perceptual side by side on the thesis's room, the
// glass, the bunny and the bright room: each frame's median time (frames
// alternating between the rules), its rays and camera rays, and its mean
// FLIP against a converged full trace (256 jittered samples, depth 16), with
// the perceptual rule's ratios to auto's.
void perceptualSection(const std::string& scenes, bool quick);

}  // namespace glint::bench
