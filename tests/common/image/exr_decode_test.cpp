// OpenEXR textures: scanline and tiled files, RGB and luminance, written
// here with OpenEXR's own writer, decode to the texels their linear values
// round to; a file cut short, a deep or multi-part file, or one over the
// texture limit is refused with the texture's name.
#include "common/image/image_decode.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfTiledRgbaFile.h>
#include <gtest/gtest.h>

#include "common/base/error.h"
#include "common/scene/scene_budget.h"
#include "tests/support/hostile_images.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

// Linear values and the texel bytes they must read as: x / 255 rounded,
// clamped to [0, 1] (2.0 and -1.0), with a half's precision kept in mind
// (0.25 and 0.5 are exact halves: 63.75 -> 64 and 127.5 -> 128).
constexpr float kValues[] = {0.0f, 0.25f, 0.5f, 1.0f, 2.0f, -1.0f};
constexpr std::uint8_t kBytes[] = {0, 64, 128, 255, 255, 0};
constexpr int kWidth = 37, kHeight = 21;  // not a multiple of the tile size

// Pixel (x, y)'s channel c: one of kValues, different per channel.
int valueIndex(int x, int y, int c) {
  return (x + 2 * y + 3 * c) % 6;
}

void fill(Imf::Array2D<Imf::Rgba>& p) {
  p.resizeErase(kHeight, kWidth);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      p[y][x] = Imf::Rgba(kValues[valueIndex(x, y, 0)], kValues[valueIndex(x, y, 1)], kValues[valueIndex(x, y, 2)]);
    }
  }
}

std::string readAndRemove(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  std::filesystem::remove(path);
  return bytes.str();
}

// A scanline file whose data window starts at (origin, origin).
std::string scanlineExr(Imf::RgbaChannels channels, int origin) {
  const auto path = test::scratchPath("scanline.exr");
  const Imath::Box2i window({origin, origin}, {origin + kWidth - 1, origin + kHeight - 1});
  Imf::Array2D<Imf::Rgba> p;
  fill(p);
  {
    Imf::RgbaOutputFile out(
        path.c_str(),
        Imf::Header(window, window, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, Imf::ZIP_COMPRESSION), channels);
    out.setFrameBuffer(&p[0][0] - origin - origin * kWidth, 1, kWidth);
    out.writePixels(kHeight);
  }
  return readAndRemove(path);
}

std::string tiledExr() {
  const auto path = test::scratchPath("tiled.exr");
  Imf::Array2D<Imf::Rgba> p;
  fill(p);
  {
    Imf::TiledRgbaOutputFile out(path.c_str(), kWidth, kHeight, 16, 8, Imf::ONE_LEVEL, Imf::ROUND_DOWN, Imf::WRITE_RGB);
    out.setFrameBuffer(&p[0][0], 1, kWidth);
    out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
  }
  return readAndRemove(path);
}

void expectTexels(const Image& image) {
  ASSERT_EQ(image.width, kWidth);
  ASSERT_EQ(image.height, kHeight);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      for (int c = 0; c < 3; ++c) {
        const std::size_t at = (static_cast<std::size_t>(y) * kWidth + x) * 3 + c;
        ASSERT_EQ(image.rgb[at], kBytes[valueIndex(x, y, c)]) << x << "," << y << " channel " << c;
      }
    }
  }
}

std::string decodeError(const std::string& bytes, SceneBudget& budget) {
  try {
    decodeImage(bytes, "t.exr", budget);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(decoded without error)";
}

TEST(ExrDecode, ScanlinesDecodeToTheirTexelsFromTheDataWindowsCorner) {
  SceneBudget budget;
  expectTexels(decodeImage(scanlineExr(Imf::WRITE_RGB, 0), "t.exr", budget));
  expectTexels(decodeImage(scanlineExr(Imf::WRITE_RGBA, -5), "t.exr", budget));
  EXPECT_EQ(budget.used(), 2u * kWidth * kHeight * 3);
}

TEST(ExrDecode, TilesDecodeToTheSameTexels) {
  SceneBudget budget;
  expectTexels(decodeImage(tiledExr(), "t.exr", budget));
}

TEST(ExrDecode, LuminanceFillsAllThreeChannels) {
  SceneBudget budget;
  const Image image = decodeImage(scanlineExr(Imf::WRITE_Y, 0), "t.exr", budget);
  ASSERT_EQ(image.rgb.size(), std::size_t{kWidth} * kHeight * 3);
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
    EXPECT_EQ(image.rgb[i + 1], image.rgb[i]);
    EXPECT_EQ(image.rgb[i + 2], image.rgb[i]);
  }
  // Pixel 0's R, G, B are 0, 1 and 0: Y = 0.7152 (Rec. 709's weight of G).
  EXPECT_NEAR(image.rgb[0], 0.7152f * 255.0f, 1.0f);
}

TEST(ExrDecode, AFileCutShortIsRefusedWithItsName) {
  const std::string whole = scanlineExr(Imf::WRITE_RGB, 0);
  for (const std::size_t keep : {std::size_t{4}, std::size_t{40}, whole.size() / 2, whole.size() - 1}) {
    SceneBudget budget;
    const std::string error = decodeError(whole.substr(0, keep), budget);
    EXPECT_EQ(error.rfind("t.exr: ", 0), 0u) << keep << ": " << error;
    EXPECT_NE(error.find("OpenEXR"), std::string::npos) << keep << ": " << error;
  }
}

TEST(ExrDecode, AnImageOverTheTextureLimitIsRefusedBeforeDecoding) {
  LoadLimits limits;
  limits.maxTexturePixels = kWidth * kHeight - 1;
  SceneBudget budget(limits);
  const std::string error = decodeError(tiledExr(), budget);
  EXPECT_NE(error.find("image of 37x21 pixels is over the limit"), std::string::npos) << error;
  EXPECT_EQ(budget.used(), 0u);
}


// A tiled file whose data window says 8192 x 8192 in 16 x 8 tiles (524,288
// chunks) with the offsets of 9 after it: the chunk count is checked against
// the file before the image is admitted or allocated (786 MiB of floats were
// allocated before the check).
TEST(ExrDecode, MoreChunksThanTheFileHoldsAreRefusedBeforeAnythingIsAllocated) {
  const std::string bytes = test::exrWithLargeWindow(tiledExr());
  ASSERT_NE(bytes, tiledExr());
  SceneBudget budget;
  const std::string error = decodeError(bytes, budget);
  EXPECT_NE(error.find("t.exr: OpenEXR image has more chunks than bytes"), std::string::npos) << error;
  EXPECT_EQ(budget.used(), 0u);
}

// OpenEXR's buffers for a chunk (packed and unpacked) count against the
// scene's limit while the file decodes, beside the texels the image keeps;
// the texture is decoded straight to its bytes, with no float image held.
TEST(ExrDecode, TheChunksBuffersAreChargedWhileItDecodes) {
  const std::size_t texels = std::size_t{kWidth} * kHeight * Image::kBytesPerTexel;
  LoadLimits tight;
  tight.maxSceneBytes = texels;
  SceneBudget budget(tight);
  const std::string error = decodeError(tiledExr(), budget);
  EXPECT_NE(error.find("t.exr: the scene would hold"), std::string::npos) << error;
  EXPECT_NE(error.find("while it decodes"), std::string::npos) << error;
  SceneBudget roomy;
  expectTexels(decodeImage(tiledExr(), "t.exr", roomy));
  EXPECT_EQ(roomy.used(), texels);
}

}  // namespace
}  // namespace glint
