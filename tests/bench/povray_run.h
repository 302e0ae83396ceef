#pragma once

#include <filesystem>
#include <string>

namespace glint::bench {

// One POV-Ray 3.7 render, a peer of the bench. Two times: the whole process
// as a user waits for it (start-up, parsing, writing the PNG), and POV-Ray's
// own rendering time (its "Radiosity Time", the pretrace, plus its "Trace
// Time"), the work that compares with a Glint frame. Negative when POV-Ray
// fails or prints no trace time.
struct PovrayRun {
  double processMs = -1.0;
  double renderMs = -1.0;
};

// Whether a povray command is on the PATH.
bool povrayInstalled();

// Renders `pov` into the PNG `out` at width x height on 2 threads, with no
// display and no progress lines, adding `options` (POV-Ray's own switches:
// "+A0.0 +AM1 +R2 +J1.0" for 4 jittered samples a pixel, "Declare=N=V" for a
// value the scene reads).
PovrayRun runPovray(const std::filesystem::path& pov, const std::filesystem::path& out, int width, int height,
                    const std::string& options);

}  // namespace glint::bench
