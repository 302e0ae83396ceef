#pragma once

#include <optional>
#include <string>
#include <vector>

#include "client/accuracy/accuracy_report.h"
#include "client/commands/frame_overrides.h"
#include "client/raster/headless_gl.h"
#include "client/farm/tile_backend.h"

namespace glint {

// Options of `glint accuracy`.
struct AccuracyOptions {
  std::string scene;
  std::string outDir;
  std::vector<std::string> vary;  // "KEY=V1,V2,..." each; none: the default sweep
  int referenceSamples = 256;
  int frames = 3;        // frames per row; the median time is reported
  FrameOverrides frame;  // the base every row varies one setting of
  int threads = 0;
  // --server ...: the rows are traced by glintd (their images are the 8-bit
  // frames, so errors below 1/255 are not seen); the reference in process.
  RemoteOptions remote;
  std::optional<gl::GlBackend> gl;  // --gl: the hybrid rows' headless OpenGL; unset: the default
  std::optional<AccuracyMetric> metric;  // --metric: the plot's error axis and the Pareto front's; unset: flip
};

// Renders a reference and every setting of the sweep, measures each row's
// error (RMSE, PSNR, FLIP) against the reference and its time, and writes
// accuracy.csv, the images (PFM and PNG), the error images and FLIP maps, the
// plot and report.md to outDir
// (docs/accuracy.md). Throws InputError for bad input, before rendering.
void runAccuracy(const AccuracyOptions& options);

}  // namespace glint
