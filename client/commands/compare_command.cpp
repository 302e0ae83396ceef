#include "client/commands/compare_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "common/base/error.h"
#include "common/metrics/image_metrics.h"
#include "common/image/image_read.h"
#include "common/image/image_write.h"

namespace glint {

namespace {

// The FLIP map of the two files: HDR-FLIP when both hold linear floats (and
// the reference's luminance gives an exposure range), LDR-FLIP of the light
// a display shows otherwise; `how` says which, for the printed line.
FlipMap flipOf(const ImageFile& reference, const ImageFile& test, double ppd, std::string& how) {
  if (!reference.eightBit && !test.eightBit) {
    const HdrExposures e = hdrExposures(reference.values);
    if (e.count > 0) {
      char text[128];
      std::snprintf(text, sizeof text, "HDR-FLIP, exposures %.2f to %.2f in %d steps; ", e.start, e.stop, e.count);
      how = text;
      return hdrFlip(reference.values, test.values, e, ppd);
    }
  }
  how = "";
  return flip(displayedLight(reference), displayedLight(test), ppd);
}

}  // namespace

void runCompare(const CompareOptions& options) {
  if (!options.errorMap.empty() && std::filesystem::path(options.errorMap).extension() != ".png") {
    throw UsageError("-o " + options.errorMap + ": the error map is written as a PNG; name it .png");
  }
  const ImageFile reference = readImageFile(options.reference), test = readImageFile(options.test);
  std::string how;
  const FlipMap map = flipOf(reference, test, options.pixelsPerDegree, how);
  const FlipStats stats = flipStats(map);
  // RMSE over the values the files hold (8-bit values / 255, as PSNR of 8-bit
  // images is quoted), or over displayed light when one file is 8-bit and
  // the other holds floats.
  const bool sameKind = reference.eightBit == test.eightBit;
  const ImageError error = sameKind ? compareImages(test.values, reference.values)
                                    : compareImages(displayedLight(test), displayedLight(reference));
  std::printf("FLIP %.6f (%s95th percentile %.6f, 99th %.6f; %.1f pixels per degree)\n", stats.mean, how.c_str(),
              stats.p95, stats.p99, options.pixelsPerDegree);
  std::printf("RMSE %.6f%s\n", error.rmse, sameKind ? "" : " (of displayed light: one file is 8-bit, one float)");
  if (std::isinf(error.psnrDb)) {
    std::printf("PSNR inf dB (identical)\n");
  } else {
    std::printf("PSNR %.2f dB\n", error.psnrDb);
  }
  if (!options.errorMap.empty()) writePng(options.errorMap, magmaImage(map), Encoding::kSrgb);
}

}  // namespace glint
