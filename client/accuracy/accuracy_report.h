#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "common/base/enum_words.h"
#include "common/metrics/flip.h"
#include "common/metrics/image_metrics.h"
#include "common/render/frame.h"
#include "common/render/ray_stats.h"

namespace glint {

// The error a sweep's plot, Pareto front and summary judge rows by: FLIP's
// mean (what a viewer sees) or the RMSE of linear values.
enum class AccuracyMetric { kFlip, kRmse };

template <>
struct EnumWords<AccuracyMetric> {
  static constexpr std::array<std::pair<AccuracyMetric, std::string_view>, 2> kWords{
      {{AccuracyMetric::kFlip, "flip"}, {AccuracyMetric::kRmse, "rmse"}}};
};

// One rendered setting of an accuracy sweep.
struct AccuracyRow {
  std::string name;   // the key varied ("samples")
  std::string value;  // its value in this row ("16")
  bool sceneSetting = false;  // the scene's own value
  double timeMs = 0.0;        // median frame time, with fieldMs
  double fieldMs = 0.0;       // filling the row's irradiance field (0: it reads none)
  RayStats rays;
  ImageError error;
  FlipStats flip;     // of the image as a display shows it (Encoder::displayed)
  std::string image;  // file name of the row's PNG in the output folder
};

// The reference the rows are measured against, and its own error.
struct AccuracyReference {
  int samples = 0;
  std::string pattern;  // its samples' pattern: the scene's jittered or sobol, else jittered
  std::string light;  // how it carries light: "max depth 16, no weight cut-off"
  double ownRmse = 0.0;  // estimated from two half-sample references
  double halvesFlip = 0.0;  // the mean FLIP of the two halves against each other
  double timeMs = 0.0;
};

// A false-colour picture of per-pixel errors on a fixed scale (black 0, blue
// 1/255, green 4/255, yellow 8/255: visible, red 32/255 and more), so that
// images of different rows compare.
FrameImage errorImage(const std::vector<float>& perPixel, int width, int height);

// A row's error by `metric`.
double errorOf(const AccuracyRow& row, AccuracyMetric metric);
// The reference's own error by `metric`, estimated from its two halves
// (each errs by about sqrt(2) times the whole, their difference by 2 times).
double ownError(const AccuracyReference& reference, AccuracyMetric metric);
// Whether a row's error is within 2x of the reference's own: much of what
// it measures may be the reference's noise.
bool nearTheReferencesNoise(const AccuracyRow& row, const AccuracyReference& reference, AccuracyMetric metric);

// accuracy.csv, the plot of `metric` against time (gnuplot's data and
// script, and accuracy.png when gnuplot is installed; false when it is not)
// and report.md, in `dir`.
void writeCsv(const std::filesystem::path& dir, const std::vector<AccuracyRow>& rows);
bool writePlot(const std::filesystem::path& dir, const std::vector<AccuracyRow>& rows,
               const AccuracyReference& reference, AccuracyMetric metric);
void writeReport(const std::filesystem::path& dir, const std::string& scene, const AccuracyReference& reference,
                 const std::vector<AccuracyRow>& rows, AccuracyMetric metric, bool plotted);

// Rows no other row beats in both time and `metric`.
std::vector<bool> paretoFront(const std::vector<AccuracyRow>& rows, AccuracyMetric metric);

}  // namespace glint
