// glint accuracy: the error metrics against errors worked out by hand, the
// --vary checks, and a small sweep whose error must fall with samples the
// way sampling theory says.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "client/accuracy/accuracy_command.h"
#include "client/accuracy/accuracy_report.h"
#include "client/accuracy/accuracy_sweep.h"
#include "common/base/error.h"
#include "common/metrics/flip.h"
#include "common/metrics/image_metrics.h"
#include "common/image/image_read.h"
#include "common/scene/scene_load.h"
#include "tests/support/glint_run.h"
#include "tests/support/glintd_process.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

LinearImage image(std::vector<float> rgb, int width) {
  return {width, static_cast<int>(rgb.size() / 3 / static_cast<std::size_t>(width)), std::move(rgb)};
}

TEST(ImageMetrics, ErrorsWorkedOutByHand) {
  const LinearImage reference = image({0, 0, 0, 0, 0, 0, 0.5f, 0.5f, 0.5f}, 3);
  // Pixel 0: one channel off by 0.5; pixel 1: one channel off by 2/255; pixel 2 exact.
  const LinearImage test = image({0.5f, 0, 0, 0, 2.0f / 255.0f, 0, 0.5f, 0.5f, 0.5f}, 3);
  const ImageError e = compareImages(test, reference);
  const double squares = 0.25 + (2.0 / 255.0) * (2.0 / 255.0);
  EXPECT_NEAR(e.rmse, std::sqrt(squares / 9.0), 1e-7);
  EXPECT_NEAR(e.psnrDb, 20.0 * std::log10(1.0 / std::sqrt(squares / 9.0)), 1e-5);
  EXPECT_FLOAT_EQ(static_cast<float>(e.maxError), 0.5f);
  EXPECT_NEAR(e.over1, 2.0 / 3.0, 1e-12);  // pixels 0 and 1
  EXPECT_NEAR(e.over8, 1.0 / 3.0, 1e-12);  // pixel 0 only
  const ImageError same = compareImages(reference, reference);
  EXPECT_EQ(same.rmse, 0.0);
  EXPECT_TRUE(std::isinf(same.psnrDb));
  EXPECT_THROW(compareImages(image({0, 0, 0}, 1), reference), InputError);
}

TEST(ImageMetrics, ErrorImageRampIsFixed) {
  const FrameImage ramp = errorImage({0.0f, 1.0f / 255.0f, 8.0f / 255.0f, 1.0f}, 4, 1);
  EXPECT_EQ(std::vector<std::uint8_t>(ramp.rgb.begin(), ramp.rgb.begin() + 3), (std::vector<std::uint8_t>{0, 0, 0}));
  EXPECT_EQ(std::vector<std::uint8_t>(ramp.rgb.begin() + 3, ramp.rgb.begin() + 6),
            (std::vector<std::uint8_t>{0, 0, 255}));
  EXPECT_EQ(std::vector<std::uint8_t>(ramp.rgb.begin() + 6, ramp.rgb.begin() + 9),
            (std::vector<std::uint8_t>{255, 230, 0}));
  EXPECT_EQ(std::vector<std::uint8_t>(ramp.rgb.begin() + 9, ramp.rgb.end()), (std::vector<std::uint8_t>{255, 0, 0}));
}

std::string varyError(const std::string& text) {
  try {
    parseVary(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(taken)";
}

TEST(AccuracySweep, BadVaryValuesNameTheKeyAndWhatItTakes) {
  EXPECT_NE(varyError("colour=1").find("KEY one of samples, pattern, filter, max_depth, min_weight, mask_threshold, shadow_map"),
            std::string::npos);
  EXPECT_NE(varyError("samples=4,0").find("samples does not take '0'; it takes whole numbers in [1, 4096]"),
            std::string::npos);
  EXPECT_NE(varyError("filter=lanczos").find("it takes one of box, tent, gaussian, mitchell"), std::string::npos);
  EXPECT_NE(varyError("min_weight=2").find("it takes numbers in [0, 1]"), std::string::npos);
  EXPECT_NE(varyError("max_depth=").find("no values"), std::string::npos);
  EXPECT_EQ(parseVary("pattern=regular,jittered").values, (std::vector<std::string>{"regular", "jittered"}));
}

// The default sweep varies light_samples where a scene has a soft light.
TEST(AccuracySweep, LightSamplesVaryWhereASceneHasASoftLight) {
  const auto varies = [](const char* name) {
    const std::vector<Series> sweep = defaultSweep(loadSceneFile(test::sourcePath(name)));
    return std::any_of(sweep.begin(), sweep.end(), [](const Series& s) { return s.key == AccuracyKey::kLightSamples; });
  };
  EXPECT_TRUE(varies("scenes/soft-shadows.json"));
  EXPECT_TRUE(varies("scenes/sphere-light.json"));
  EXPECT_FALSE(varies("scenes/lights.json"));
  EXPECT_FALSE(varies("scenes/room.json"));
}

struct CsvRow {
  std::string value;
  double timeMs;
  double rmse;
  double flip, flipP95, flipP99;
};

std::vector<CsvRow> readCsv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<CsvRow> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    rows.push_back({cells.at(1), std::stod(cells.at(3)), std::stod(cells.at(9)), std::stod(cells.at(14)),
                    std::stod(cells.at(15)), std::stod(cells.at(16))});
  }
  return rows;
}

double referenceError(const fs::path& report) {
  std::ifstream in(report);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("is RMSE ");
  return at == std::string::npos ? -1.0 : std::stod(text.substr(at + 8));
}

// A sweep of `scene` (in the tree) into `dir`: one frame a row, the
// reference of `referenceSamples`, the frame `width` x `height`.
AccuracyOptions smallSweep(const std::string& scene, const fs::path& dir, std::vector<std::string> vary,
                           int referenceSamples, int width, int height) {
  AccuracyOptions o;
  o.scene = test::sourcePath(scene);
  o.outDir = dir.string();
  o.vary = std::move(vary);
  o.referenceSamples = referenceSamples;
  o.frames = 1;
  o.frame.width = width;
  o.frame.height = height;
  return o;
}

// From 16 to 64 jittered samples the error against the reference falls by
// more than 1.4x and less than 4x (plain Monte Carlo: 2x), the time rises,
// and the reference's own error is below the 64-sample row's.
TEST(Accuracy, ErrorFallsWithSamplesOnASmallScene) {
  const fs::path dir = fs::temp_directory_path() / ("glint-accuracy-" + std::to_string(::getpid()));
  AccuracyOptions o = smallSweep("scenes/glass.json", dir, {"samples=16,64", "pattern=jittered"}, 512, 64, 48);
  runAccuracy(o);
  const std::vector<CsvRow> rows = readCsv(dir / "accuracy.csv");
  ASSERT_EQ(rows.size(), 3u);
  const double ratio = rows[0].rmse / rows[1].rmse;
  EXPECT_GT(ratio, 1.4) << rows[0].rmse << " at 16 samples, " << rows[1].rmse << " at 64";
  EXPECT_LT(ratio, 4.0) << rows[0].rmse << " at 16 samples, " << rows[1].rmse << " at 64";
  EXPECT_GT(rows[1].timeMs, rows[0].timeMs);
  const double own = referenceError(dir / "report.md");
  EXPECT_GT(own, 0.0);
  EXPECT_LT(own, rows[1].rmse);
  // Every row's linear values are there to recompute the numbers from.
  const auto pfmBytes = fs::file_size(dir / "samples-64.pfm");
  EXPECT_EQ(pfmBytes, std::string("PF\n64 48\n-1.0\n").size() + 64u * 48u * 3u * sizeof(float));
  EXPECT_TRUE(fs::exists(dir / "samples-64-error.png"));
  EXPECT_TRUE(fs::exists(dir / "reference.pfm"));
  // FLIP falls with samples too, its percentiles above its mean; it is the
  // FLIP of the PNGs the sweep wrote, as glint compare reads them (through
  // sRGB, as a display shows the scene's linear values).
  EXPECT_GT(rows[0].flip, rows[1].flip);
  for (const CsvRow& r : rows) {
    EXPECT_GE(r.flipP95, r.flip);
    EXPECT_GE(r.flipP99, r.flipP95);
  }
  const double fromPngs = flipStats(flip(displayedLight(readImageFile(dir / "reference.png")),
                                         displayedLight(readImageFile(dir / "samples-16.png"))))
                              .mean;
  EXPECT_NEAR(rows[0].flip, fromPngs, 1e-6);
  EXPECT_TRUE(fs::exists(dir / "samples-64-flip.png"));
  std::ifstream script(dir / "accuracy.gp");
  const std::string gp((std::istreambuf_iterator<char>(script)), std::istreambuf_iterator<char>());
  EXPECT_NE(gp.find("mean FLIP against the reference"), std::string::npos);
  // The plot itself: gnuplot is among the packages make test installs.
  ASSERT_EQ(std::system("command -v gnuplot > /dev/null 2>&1"), 0) << "gnuplot is not installed (make deps)";
  const auto plot = readImageFile(dir / "accuracy.png");
  EXPECT_GT(plot.values.width, 100);
  EXPECT_GT(plot.values.height, 100);
  fs::remove_all(dir);
}

// The FLIP column is what a viewer sees flipping between the PNGs the sweep
// wrote, as glint compare reads them, under either encoding of the scene's
// 8-bit values (the room names linear; srgb is the format's default).
TEST(Accuracy, TheFlipColumnIsThePngsFlipUnderEitherEncoding) {
  for (const Encoding encoding : {Encoding::kSrgb, Encoding::kLinear}) {
    const fs::path dir = fs::temp_directory_path() / ("glint-accuracy-png-" + std::to_string(::getpid()));
    AccuracyOptions o = smallSweep("scenes/room.json", dir, {"samples=1,4"}, 16, 40, 30);
    o.frame.encoding = encoding;
    runAccuracy(o);
    const std::vector<CsvRow> rows = readCsv(dir / "accuracy.csv");
    ASSERT_GE(rows.size(), 2u);
    for (const char* value : {"1", "4"}) {
      const double fromPngs = flipStats(flip(displayedLight(readImageFile(dir / "reference.png")),
                                             displayedLight(readImageFile(dir / ("samples-" + std::string(value) +
                                                                                 ".png")))))
                                  .mean;
      const auto row = std::find_if(rows.begin(), rows.end(), [&](const CsvRow& r) { return r.value == value; });
      ASSERT_NE(row, rows.end()) << value;
      EXPECT_NEAR(row->flip, fromPngs, 1e-6) << value << (encoding == Encoding::kSrgb ? " srgb" : " linear");
    }
    fs::remove_all(dir);
  }
}

// The reference takes the scene's pattern (the Cornell box's sobol) and says
// its own error; a row whose error is within 2x of it is named (here 16
// samples against a 32-sample reference), a row far above it is not.
TEST(Accuracy, TheReferenceTakesTheScenesPatternAndNamesRowsNearItsNoise) {
  const fs::path dir = fs::temp_directory_path() / ("glint-accuracy-noise-" + std::to_string(::getpid()));
  AccuracyOptions o = smallSweep("scenes/cornell.json", dir, {"samples=1,16"}, 32, 48, 48);
  runAccuracy(o);
  std::ifstream in(dir / "report.md");
  const std::string report((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("Reference: 32 sobol samples per pixel"), std::string::npos) << report;
  EXPECT_NE(report.find("and FLIP about 0.0"), std::string::npos) << report;
  const std::size_t near = report.find("Within 2x of the reference's own error");
  ASSERT_NE(near, std::string::npos) << report;
  const std::string named = report.substr(near, report.find('\n', near + 1) - near);
  EXPECT_NE(named.find("samples = 16"), std::string::npos) << named;
  EXPECT_EQ(named.find("samples = 1,"), std::string::npos) << named;
  EXPECT_EQ(named.find("samples = 1."), std::string::npos) << named;
  fs::remove_all(dir);
}

// On the Cornell box the reference is the converged path trace: Whitted
// transport at the path rows' samples errs far more (the light between the
// walls it never computes: the model's error), and cutting the bounces to
// none errs more than 8 (the light cut short). The reference takes the
// scene's sobol pattern.
TEST(Accuracy, UnderPathTransportTheModelsErrorShows) {
  const fs::path dir = fs::temp_directory_path() / ("glint-accuracy-path-" + std::to_string(::getpid()));
  AccuracyOptions o =
      smallSweep("scenes/cornell.json", dir, {"transport=whitted,path", "max_bounces=0,8"}, 256, 40, 40);
  o.frame.samples = 16;
  runAccuracy(o);
  const std::vector<CsvRow> rows = readCsv(dir / "accuracy.csv");
  ASSERT_EQ(rows.size(), 4u);  // whitted, path, 0 bounces, 8 bounces
  // 40 x 40 at 16 samples (measured: RMSE 0.096 against 0.041, FLIP 0.72 against 0.089).
  EXPECT_GT(rows[0].rmse, 1.5 * rows[1].rmse) << "whitted " << rows[0].rmse << ", path " << rows[1].rmse;
  EXPECT_GT(rows[0].flip, 4.0 * rows[1].flip) << "whitted " << rows[0].flip << ", path " << rows[1].flip;
  EXPECT_GT(rows[2].rmse, rows[3].rmse) << "0 bounces " << rows[2].rmse << ", 8 bounces " << rows[3].rmse;
  std::ifstream report(dir / "report.md");
  const std::string text((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("256 sobol samples per pixel, path transport, 64 bounces"), std::string::npos) << text;
  fs::remove_all(dir);
}

// What runAccuracy refused `o` with ("(ran)" when it did not).
std::string accuracyError(const AccuracyOptions& o) {
  try {
    runAccuracy(o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(ran)";
}

// With an irradiance field the field's rows are hybrid frames drawn from it
// (not the path trace every pixel traced, mask_rule all), each against the
// converged path trace: more rays a probe err less, the field's bias stays
// within 2x the full trace's error at the same samples, and each row's time
// counts its field's fill. The field's keys refuse a Whitted scene.
TEST(Accuracy, TheFieldsRowsAreHybridFramesDrawnFromIt) {
  const fs::path dir = fs::temp_directory_path() / ("glint-accuracy-field-" + std::to_string(::getpid()));
  AccuracyOptions o = smallSweep("scenes/cornell.json", dir, {"field_rays=64,1024", "mask_rule=all"}, 256, 48, 48);
  o.frame.samples = 16;
  o.frame.field = FieldSettings{8, 256};
  runAccuracy(o);
  const std::vector<CsvRow> rows = readCsv(dir / "accuracy.csv");
  ASSERT_EQ(rows.size(), 3u);  // 64 rays, 1,024 rays, every pixel traced
  std::printf("FLIP: 64 rays %.4f, 1024 rays %.4f, path traced %.4f\n", rows[0].flip, rows[1].flip, rows[2].flip);
  EXPECT_NE(test::decodePngFile((dir / "field_rays-64.png").string()).rgb,
            test::decodePngFile((dir / "mask_rule-all.png").string()).rgb);
  EXPECT_LT(rows[1].flip, rows[0].flip);
  EXPECT_LT(rows[1].flip, 2.0 * rows[2].flip);
  std::ifstream report(dir / "report.md");
  const std::string text((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("counts the field's fill in its time"), std::string::npos) << text;
  fs::remove_all(dir);

  o.scene = test::sourcePath("scenes/room.json");
  o.frame.field.reset();
  o.vary = {"field_probes=4"};
  const std::string whitted = accuracyError(o);
  EXPECT_NE(whitted.find("--vary field_probes: the irradiance field carries path transport's light"),
            std::string::npos)
      << whitted;
  EXPECT_FALSE(fs::exists(dir));
}

// Through glintd the field's rows are filled by the servers in batches and
// drawn as in process: the same bytes, and a path-traced row after them
// still traces every pixel (the servers no longer read the field).
TEST(Accuracy, ThroughGlintdTheFieldsRowsAreTheInProcessBytes) {
  const fs::path here = fs::temp_directory_path() / ("glint-accuracy-field-here-" + std::to_string(::getpid()));
  const fs::path there = fs::temp_directory_path() / ("glint-accuracy-field-there-" + std::to_string(::getpid()));
  AccuracyOptions o;
  o.scene = test::sourcePath("scenes/cornell.json");
  o.vary = {"field_rays=64,128", "mask_rule=all"};
  o.referenceSamples = 16;
  o.frames = 1;
  o.frame.width = 32;
  o.frame.height = 32;
  o.frame.samples = 4;
  o.frame.field = FieldSettings{4, 64};
  o.outDir = here.string();
  runAccuracy(o);
  const server::test::GlintdProcess glintd({"--threads", "1"});
  o.remote.servers = {glintd.address()};
  o.outDir = there.string();
  runAccuracy(o);
  for (const char* row : {"field_rays-64.png", "field_rays-128.png", "mask_rule-all.png"}) {
    EXPECT_EQ(test::decodePngFile((there / row).string()).rgb, test::decodePngFile((here / row).string()).rgb)
        << row;
  }
  EXPECT_NE(test::decodePngFile((there / "field_rays-64.png").string()).rgb,
            test::decodePngFile((there / "mask_rule-all.png").string()).rgb);
  fs::remove_all(here);
  fs::remove_all(there);
}

// --metric rmse: the plot's axis and the front judge RMSE.
TEST(AccuracyReport, TheMetricChoosesThePlotAndTheFront) {
  std::vector<AccuracyRow> rows(2);
  rows[0].timeMs = 10.0;  // cheaper, lower RMSE, higher FLIP
  rows[0].error.rmse = 0.01;
  rows[0].flip.mean = 0.2;
  rows[1].timeMs = 20.0;
  rows[1].error.rmse = 0.02;
  rows[1].flip.mean = 0.1;
  EXPECT_EQ(paretoFront(rows, AccuracyMetric::kRmse), (std::vector<bool>{true, false}));
  EXPECT_EQ(paretoFront(rows, AccuracyMetric::kFlip), (std::vector<bool>{true, true}));
}

TEST(Accuracy, BadInputIsRefusedBeforeRendering) {
  const fs::path dir = fs::temp_directory_path() / ("glint-accuracy-bad-" + std::to_string(::getpid()));
  // The glass scene with regular sampling: square sample counts only.
  const fs::path scene = fs::temp_directory_path() / ("glint-accuracy-regular-" + std::to_string(::getpid()) + ".json");
  {
    std::ifstream in(test::sourcePath("scenes/glass.json"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("\"jittered\""), 10, "\"regular\"");
    std::ofstream(scene) << text;
  }
  AccuracyOptions o;
  o.scene = scene.string();
  o.outDir = dir.string();
  o.frame.width = 32;
  o.frame.height = 24;
  o.vary = {"samples=4,3"};
  const std::string threeRegular = accuracyError(o);
  EXPECT_NE(threeRegular.find("--vary samples=3"), std::string::npos) << threeRegular;
  EXPECT_FALSE(fs::exists(dir));
  o.vary = {"samples=4"};
  o.referenceSamples = 255;
  const std::string odd = accuracyError(o);
  EXPECT_NE(odd.find("--reference-samples 255: must be even"), std::string::npos) << odd;
  EXPECT_FALSE(fs::exists(dir));
  fs::remove(scene);
}

}  // namespace
}  // namespace glint
