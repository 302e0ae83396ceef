#pragma once

#include <string>

namespace glint::bench {

// Path transport against Blender's Cycles (Debian's blender, run as
// `blender -b --python tests/bench/cycles/glint_scene.py`) on
// scenes/cornell.json at equal samples and bounces: each renderer's time (the
// median of three runs, the two taken in turn),
// the mean FLIP and RMSE of Glint's frame and of a second Cycles frame (another
// seed: the noise floor) against Cycles' first, and the mean radiance of each
// surface in both. Skipped, saying so, where blender is not installed.
void transportSection(const std::string& scenes, bool quick);

}  // namespace glint::bench
