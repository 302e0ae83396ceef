// Image files as glint compare and glint accuracy read them: a Radiance HDR
// holds linear light above 1, read as the file holds it.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include "common/base/error.h"
#include "common/image/image_read.h"

namespace glint {
namespace {

TEST(ImageRead, ARadianceHdrReadsAsLinearLightAboveOne) {
  // Values RGBE stores exactly: one exponent per pixel, 8 bits of mantissa.
  const std::vector<float> rgb{2.5f, 0.25f, 7.0f, 0.5f, 0.125f, 0.0f, 16.0f, 16.0f, 16.0f, 0.75f, 1.5f, 3.0f};
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "glint-image-read-test.hdr";
  ASSERT_NE(stbi_write_hdr(path.c_str(), 2, 2, 3, rgb.data()), 0);
  const ImageFile file = readImageFile(path);
  std::filesystem::remove(path);
  EXPECT_FALSE(file.eightBit);
  EXPECT_EQ(file.values.width, 2);
  EXPECT_EQ(file.values.height, 2);
  EXPECT_EQ(file.values.rgb, rgb);
  EXPECT_EQ(displayedLight(file).rgb, rgb);  // linear light: no sRGB decoding
}

TEST(ImageRead, ATruncatedHdrHeaderIsRefusedByName) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "glint-image-read-bad.hdr";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fputs("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", f);
    std::fclose(f);
  }
  try {
    readImageFile(path);
    ADD_FAILURE() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace glint
