#pragma once

#include <string>

namespace glint::bench {

// The irradiance field against path tracing, at equal error: on
// scenes/cornell.json and scenes/room-path.json, the path trace's mean FLIP
// against its own converged frame at 1, 2, 4 ... samples (each time the
// median of three runs), and the tracer's frame with the irradiance field
// (the hybrid frame's shading: Whitted's direct light, the field's indirect
// light, a path where the field cannot decide; every pixel traced) for
// several field densities and samples, its time the field's and the frame's
// apart; then the hybrid frame that draws the field with OpenGL (FLIP as
// displayed, against the path trace's curve as displayed), its first frame
// (with the field's filling) and a later one apart. Each row gives the path
// trace's time to the same FLIP (between the two sample counts around it,
// log-linear) and the ratio. Where the scene has a .pov beside it (the
// room: scenes/room-path.pov) and `povray` is set, POV-Ray 3.7's radiosity
// renders it at several settings, each FLIP as displayed against the same
// path trace, and the hybrid frame's first frame is timed against POV-Ray's
// fastest setting at equal FLIP. 640 x 480 (--quick: 160 x 120).
void indirectSection(const std::string& scenes, bool quick, bool povray);

}  // namespace glint::bench
