// The float outputs: an .exr reads back (with OpenEXR) as the float image
// rounded to half, a .pfm as the floats themselves; extensions choose the
// format and any other is refused by name.
#include "client/commands/output_file.h"

#include <filesystem>
#include <fstream>

#include <Imath/half.h>
#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <gtest/gtest.h>

#include "common/base/error.h"
#include "common/scene/scene_load.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

// Values below, inside and above [0, 1], each pixel different.
LinearImage someImage(int width, int height) {
  LinearImage image{width, height, std::vector<float>(static_cast<std::size_t>(width * height * 3))};
  for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = static_cast<float>(i) * 0.37f - 3.0f;
  return image;
}

TEST(OutputFile, ExrReadsBackAsTheImageInHalfFloat) {
  const fs::path path = fs::temp_directory_path() / "glint_output_test.exr";
  const LinearImage image = someImage(7, 5);
  writeExr(path, image);
  Imf::RgbaInputFile file(path.c_str());
  const Imath::Box2i window = file.dataWindow();
  ASSERT_EQ(window.max.x - window.min.x + 1, 7);
  ASSERT_EQ(window.max.y - window.min.y + 1, 5);
  Imf::Array2D<Imf::Rgba> pixels(5, 7);
  file.setFrameBuffer(&pixels[0][0], 1, 7);
  file.readPixels(window.min.y, window.max.y);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) {
      const float* expected = &image.rgb[static_cast<std::size_t>((y * 7 + x) * 3)];
      EXPECT_EQ(float(pixels[y][x].r), float(Imath::half(expected[0]))) << x << "," << y;
      EXPECT_EQ(float(pixels[y][x].g), float(Imath::half(expected[1]))) << x << "," << y;
      EXPECT_EQ(float(pixels[y][x].b), float(Imath::half(expected[2]))) << x << "," << y;
    }
  }
  EXPECT_FALSE(fs::exists(path.string() + ".partial"));
  fs::remove(path);
}

// What glint writes as EXR a scene takes as its environment: each texel the
// half-rounded value times 2^exposure, a negative one as 0.
TEST(OutputFile, AnExrIsAnEnvironmentImage) {
  const fs::path dir = fs::temp_directory_path() / "glint_output_environment";
  fs::create_directories(dir);
  const LinearImage image = someImage(6, 3);
  writeExr(dir / "sky.exr", image);
  std::ofstream(dir / "scene.json") << R"({"glint": 1, "image": {"width": 8, "height": 8},
    "camera": {"eye": [0, 0, 0], "look_at": [0, 0, -1]}, "environment": {"file": "sky.exr", "exposure": -1},
    "objects": []})";
  const Scene scene = loadSceneFile(dir / "scene.json");
  ASSERT_NE(scene.environment, nullptr);
  ASSERT_EQ(scene.environment->width, 6);
  ASSERT_EQ(scene.environment->height, 3);
  for (std::size_t i = 0; i < image.rgb.size(); ++i) {
    const float half = float(Imath::half(image.rgb[i]));
    EXPECT_EQ(scene.environment->rgb[i], half > 0.0f ? half * 0.5f : 0.0f) << i;
  }
  fs::remove_all(dir);
}

TEST(OutputFile, PfmHoldsTheFloatsBottomUp) {
  const fs::path path = fs::temp_directory_path() / "glint_output_test.pfm";
  const LinearImage image = someImage(3, 2);
  writeOutput(path, OutputFormat::kPfm, FrameImage{}, image);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string header = "PF\n3 2\n-1.0\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  std::vector<float> values(18);
  ASSERT_EQ(bytes.size(), header.size() + sizeof(float) * values.size());
  std::memcpy(values.data(), bytes.data() + header.size(), sizeof(float) * values.size());
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(values[static_cast<std::size_t>(i)], image.rgb[static_cast<std::size_t>(9 + i)]);  // bottom row first
    EXPECT_EQ(values[static_cast<std::size_t>(9 + i)], image.rgb[static_cast<std::size_t>(i)]);
  }
  fs::remove(path);
}

TEST(OutputFile, TheExtensionChoosesTheFormat) {
  EXPECT_EQ(outputFormat("-o", "a/b.png"), OutputFormat::kPng);
  EXPECT_EQ(outputFormat("-o", "b.EXR"), OutputFormat::kExr);
  EXPECT_EQ(outputFormat("-o", "b.pfm"), OutputFormat::kPfm);
  for (const char* bad : {"b.jpg", "b", "b.png.tmp"}) {
    try {
      outputFormat("-o", bad);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("-o ") + bad + ": glint writes .png, .exr, .pfm"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace glint
