#pragma once

#include <string>

#include "common/metrics/flip.h"

namespace glint {

// Options of `glint compare`.
struct CompareOptions {
  std::string reference;
  std::string test;
  std::string errorMap;  // -o: the FLIP map as a PNG; empty: none
  double pixelsPerDegree = kFlipPixelsPerDegree;
};

// Prints how far TEST is from REFERENCE (images of one size, any format
// readImageFile reads): the mean FLIP (HDR-FLIP when both hold linear
// floats, LDR-FLIP of what a display shows otherwise) with its 95th and 99th
// percentiles, the RMSE and the PSNR, one line each. Throws InputError for unreadable files or
// sizes that differ, UsageError for a map that is not a .png.
void runCompare(const CompareOptions& options);

}  // namespace glint
