// glint compare: the FLIP, RMSE and PSNR lines for PNG, EXR and PFM files,
// the error map, and the errors a user meets.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/glint_run.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::runGlint;

std::string fixture(const std::string& name) { return test::sourcePath("tests/data/flip/" + name); }

// The number after `word` at the start of a line of `output`.
double valueAfter(const std::string& output, const std::string& word) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(output, m, std::regex("(^|\n)" + word + " ([0-9.]+|inf)"))) << output;
  return m.size() > 2 ? std::stod(m[2].str()) : -1.0;
}

class CompareCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratchPath("compare");
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

// The room's hybrid frame against its full trace: NVIDIA's FLIP tool 1.6
// prints a mean of 0.043208 for these two PNGs (as flip_test records).
TEST_F(CompareCommand, PrintsFlipRmseAndPsnrAndWritesTheMap) {
  const auto run = runGlint("compare " + fixture("room_full.png") + " " + fixture("room_hybrid.png") + " -o " +
                            path("map.png"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NEAR(valueAfter(run.output, "FLIP"), 0.043208, 2e-6);
  const double rmse = valueAfter(run.output, "RMSE");
  EXPECT_GT(rmse, 0.0);
  EXPECT_NEAR(valueAfter(run.output, "PSNR"), 20.0 * std::log10(1.0 / rmse), 0.01);
  const Image map = test::decodePngFile(path("map.png"));
  EXPECT_EQ(map.width, 96);
  EXPECT_EQ(map.height, 64);
}

TEST_F(CompareCommand, IdenticalImagesShowNoError) {
  const auto run = runGlint("compare " + fixture("checker.png") + " " + fixture("checker.png"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(valueAfter(run.output, "FLIP"), 0.0);
  EXPECT_NE(run.output.find("PSNR inf dB"), std::string::npos) << run.output;
}

// One render written as PFM (float) and EXR (half float): the same light,
// FLIP nearly 0; the viewing distance is an option.
TEST_F(CompareCommand, ReadsFloatImages) {
  const std::string scene = test::sourcePath("scenes/room.json");
  for (const char* ext : {".pfm", ".exr"}) {
    ASSERT_EQ(runGlint("render " + scene + " --size 64x48 -q -o " + path(std::string("room") + ext)).status, 0);
  }
  const auto run = runGlint("compare " + path("room.pfm") + " " + path("room.exr") + " --ppd 30");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_LT(valueAfter(run.output, "FLIP"), 0.01);
  EXPECT_NE(run.output.find("30.0 pixels per degree"), std::string::npos) << run.output;
}

TEST_F(CompareCommand, BadInputIsAClearError) {
  const auto missing = runGlint("compare " + fixture("room_full.png") + " " + path("missing.png"));
  EXPECT_EQ(missing.status, 1) << missing.output;  // a file, not the command line
  EXPECT_NE(missing.output.find("missing.png"), std::string::npos) << missing.output;
  ASSERT_EQ(runGlint("render " + test::sourcePath("scenes/room.json") + " --size 32x24 -q -o " + path("small.png"))
                .status,
            0);
  const auto differ = runGlint("compare " + fixture("room_full.png") + " " + path("small.png"));
  EXPECT_EQ(differ.status, 1);
  EXPECT_NE(differ.output.find("different sizes cannot be compared (96x64 and 32x24)"), std::string::npos)
      << differ.output;
  std::ofstream(path("text.png")) << "not an image";
  const auto garbage = runGlint("compare " + fixture("room_full.png") + " " + path("text.png"));
  EXPECT_EQ(garbage.status, 1);
  EXPECT_NE(garbage.output.find("text.png"), std::string::npos) << garbage.output;
  const auto map = runGlint("compare " + fixture("room_full.png") + " " + fixture("room_full.png") + " -o " +
                            path("map.jpg"));
  EXPECT_EQ(map.status, 2);
  EXPECT_FALSE(fs::exists(path("map.jpg")));
}

}  // namespace
}  // namespace glint
