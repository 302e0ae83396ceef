#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "common/render/frame.h"
#include "common/image/image_metrics.h"
#include "common/render/ray_stats.h"

namespace glint {

// One rendered setting of an accuracy sweep.
struct AccuracyRow {
  std::string name;   // the key varied ("samples")
  std::string value;  // its value in this row ("16")
  bool sceneSetting = false;  // the scene's own value
  double timeMs = 0.0;        // median frame time
  RayStats rays;
  ImageError error;
  std::string image;  // file name of the row's PNG in the output folder
};

// The reference the rows are measured against, and its own error.
struct AccuracyReference {
  int samples = 0;
  int maxDepth = 0;
  double ownRmse = 0.0;  // estimated from two half-sample references
  double timeMs = 0.0;
};

// A false-colour picture of per-pixel errors on a fixed scale (black 0, blue
// 1/255, green 4/255, yellow 8/255: visible, red 32/255 and more), so that
// images of different rows compare.
FrameImage errorImage(const std::vector<float>& perPixel, int width, int height);

// accuracy.csv, the plot (gnuplot's data and script, and accuracy.png when
// gnuplot is installed; false when it is not) and report.md, in `dir`.
void writeCsv(const std::filesystem::path& dir, const std::vector<AccuracyRow>& rows);
bool writePlot(const std::filesystem::path& dir, const std::vector<AccuracyRow>& rows, double referenceRmse);
void writeReport(const std::filesystem::path& dir, const std::string& scene, const AccuracyReference& reference,
                 const std::vector<AccuracyRow>& rows, bool plotted);

// Rows no other row beats in both time and error.
std::vector<bool> paretoFront(const std::vector<AccuracyRow>& rows);

}  // namespace glint
