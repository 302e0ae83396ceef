// The outputs: an .exr reads back (with OpenEXR) as the float image
// rounded to half, a .pfm as the floats themselves, a .png says how its
// values hold light (checked chunk by chunk, each CRC by zlib); extensions
// choose the format and any other is refused by name.
#include "client/commands/output_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include <Imath/half.h>
#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include "common/base/error.h"
#include "common/image/image_read.h"
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
  writeOutput(path, OutputFormat::kPfm, FrameImage{}, image, Encoding::kLinear);
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

std::uint32_t bigEndian(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

// A PNG's chunks, type -> data, each CRC checked; in `order`, their types.
std::map<std::string, std::string> pngChunks(const fs::path& path, std::vector<std::string>& order) {
  std::ifstream in(path, std::ios::binary);
  const std::string png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::map<std::string, std::string> chunks;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t length = bigEndian(png, at);
    const std::string typeAndData = png.substr(at + 4, 4 + length);
    const auto crc = static_cast<std::uint32_t>(
        crc32(0L, reinterpret_cast<const Bytef*>(typeAndData.data()), static_cast<uInt>(typeAndData.size())));
    EXPECT_EQ(crc, bigEndian(png, at + 8 + length)) << typeAndData.substr(0, 4);
    order.push_back(typeAndData.substr(0, 4));
    chunks[order.back()] = typeAndData.substr(4);
    at += 12 + length;
  }
  return chunks;
}

// An sRGB PNG says so (sRGB, with gAMA 1/2.2 and cHRM beside it for
// readers that know only those); a linear one says gamma 1.0 and the sRGB
// primaries; both before the image data, and the pixels are unchanged.
TEST(OutputFile, APngSaysHowItsValuesHoldLight) {
  const FrameImage image{3, 2, {0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130, 140, 150, 160, 255}};
  const fs::path path = fs::temp_directory_path() / "glint_output_test.png";
  for (Encoding encoding : {Encoding::kSrgb, Encoding::kLinear}) {
    writeOutput(path, OutputFormat::kPng, image, LinearImage{}, encoding);
    std::vector<std::string> order;
    const std::map<std::string, std::string> chunks = pngChunks(path, order);
    ASSERT_GE(order.size(), 4u);
    EXPECT_EQ(order.front(), "IHDR");
    EXPECT_EQ(order.back(), "IEND");
    const std::size_t data = std::find(order.begin(), order.end(), "IDAT") - order.begin();
    for (const char* colour : {"gAMA", "cHRM"}) {
      ASSERT_TRUE(chunks.count(colour)) << colour;
      EXPECT_LT(std::find(order.begin(), order.end(), colour) - order.begin(), static_cast<long>(data)) << colour;
    }
    const bool srgb = encoding == Encoding::kSrgb;
    EXPECT_EQ(bigEndian(chunks.at("gAMA"), 0), srgb ? 45455u : 100000u);
    EXPECT_EQ(chunks.count("sRGB"), srgb ? 1u : 0u);
    EXPECT_EQ(bigEndian(chunks.at("cHRM"), 0), 31270u);  // D65's x
    EXPECT_EQ(bigEndian(chunks.at("cHRM"), 8), 64000u);  // red's x
    const ImageFile read = readImageFile(path);
    ASSERT_EQ(read.values.rgb.size(), image.rgb.size());
    for (std::size_t i = 0; i < image.rgb.size(); ++i) EXPECT_EQ(std::lround(read.values.rgb[i] * 255.0f), image.rgb[i]);
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
