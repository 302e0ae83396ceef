#include "client/compare_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "client/usage_error.h"
#include "common/image/image_metrics.h"
#include "common/image/image_read.h"
#include "common/image/image_write.h"

namespace glint {

void runCompare(const CompareOptions& options) {
  if (!options.errorMap.empty() && std::filesystem::path(options.errorMap).extension() != ".png") {
    throw UsageError("-o " + options.errorMap + ": the error map is written as a PNG; name it .png");
  }
  const ImageFile reference = readImageFile(options.reference), test = readImageFile(options.test);
  const LinearImage referenceLight = displayLight(reference), testLight = displayLight(test);
  const FlipMap map = flip(referenceLight, testLight, options.pixelsPerDegree);
  const FlipStats stats = flipStats(map);
  // RMSE over the values the files hold (8-bit values / 255, as PSNR of 8-bit
  // images is quoted), or over displayed light when one file is 8-bit and
  // the other holds floats.
  const bool sameKind = reference.eightBit == test.eightBit;
  const ImageError error =
      sameKind ? compareImages(test.values, reference.values) : compareImages(testLight, referenceLight);
  std::printf("FLIP %.6f (95th percentile %.6f, 99th %.6f; %.1f pixels per degree)\n", stats.mean, stats.p95,
              stats.p99, options.pixelsPerDegree);
  std::printf("RMSE %.6f%s\n", error.rmse, sameKind ? "" : " (of displayed light: one file is 8-bit, one float)");
  if (std::isinf(error.psnrDb)) {
    std::printf("PSNR inf dB (identical)\n");
  } else {
    std::printf("PSNR %.2f dB\n", error.psnrDb);
  }
  if (!options.errorMap.empty()) writePng(options.errorMap, magmaImage(map));
}

}  // namespace glint
