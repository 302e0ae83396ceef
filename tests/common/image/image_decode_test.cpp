// Image textures from memory: PNG, BMP, JPEG, TGA and Radiance HDR (written
// here with stb_image_write) decode to the texels written; no other format
// reaches the decoder, and memory follows the bytes that arrived: a file
// that claims more than it holds is refused before the decoder allocates
// for the claim.
#include "common/image/image_decode.h"
#include "common/image/image_write.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include "common/base/error.h"
#include "common/image/jpeg_decode.h"
#include "common/scene/scene_budget.h"
#include "tests/support/hostile_images.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

std::string decodeError(const std::string& bytes) {
  SceneBudget budget;
  try {
    decodeImage(bytes, "t.png", budget);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(decoded without error)";
}

// This process's peak virtual memory, in KiB (/proc/self/status VmPeak).
long peakVirtualKb() {
  std::ifstream in("/proc/self/status");
  std::string key;
  long kb = -1;
  while (in >> key) {
    if (key == "VmPeak:") in >> kb;
  }
  return kb;
}

TEST(ImageDecode, PngRoundTripKeepsEveryByte) {
  FrameImage image{5, 3, std::vector<std::uint8_t>(45)};
  for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = static_cast<std::uint8_t>(i * 37);
  const auto path = std::filesystem::temp_directory_path() / "glint-image-io-test.png";
  writePng(path, image, Encoding::kSrgb);
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  std::filesystem::remove(path);
  SceneBudget budget;
  const Image decoded = decodeImage(bytes.str(), "t.png", budget);
  EXPECT_EQ(decoded.width, 5);
  EXPECT_EQ(decoded.height, 3);
  EXPECT_EQ(decoded.rgb, image.rgb);
  EXPECT_EQ(budget.used(), 45u);
}

// What stb_image_write puts through its callback, as a file's bytes.
void appendTo(void* out, void* data, int size) {
  static_cast<std::string*>(out)->append(static_cast<char*>(data), size);
}

// An 8x6 image of distinct colours, smooth enough for JPEG at quality 100.
std::vector<std::uint8_t> gradient() {
  std::vector<std::uint8_t> rgb;
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 8; ++x) rgb.insert(rgb.end(), {std::uint8_t(30 * x), std::uint8_t(40 * y), 128});
  }
  return rgb;
}

TEST(ImageDecode, JpegTgaAndHdrDecodeToTheTexelsWritten) {
  const std::vector<std::uint8_t> rgb = gradient();
  std::string tga, jpeg, hdr;
  ASSERT_NE(stbi_write_tga_to_func(appendTo, &tga, 8, 6, 3, rgb.data()), 0);
  ASSERT_NE(stbi_write_jpg_to_func(appendTo, &jpeg, 8, 6, 3, rgb.data(), 100), 0);
  std::vector<float> linear;
  for (const std::uint8_t v : rgb) linear.push_back(v / 255.0f);
  linear[0] = 7.5f;  // brighter than a texture holds: clamped to 1
  ASSERT_NE(stbi_write_hdr_to_func(appendTo, &hdr, 8, 6, 3, linear.data()), 0);
  SceneBudget budget;
  const Image fromTga = decodeImage(tga, "t.tga", budget);
  EXPECT_EQ(fromTga.width, 8);
  EXPECT_EQ(fromTga.height, 6);
  EXPECT_EQ(fromTga.rgb, rgb);
  const Image fromJpeg = decodeImage(jpeg, "t.jpg", budget);
  const Image fromHdr = decodeImage(hdr, "t.hdr", budget);
  ASSERT_EQ(fromJpeg.rgb.size(), rgb.size());
  ASSERT_EQ(fromHdr.rgb.size(), rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    EXPECT_NEAR(fromJpeg.rgb[i], rgb[i], 6) << "JPEG byte " << i;               // lossy, at its best quality
    EXPECT_NEAR(fromHdr.rgb[i], i == 0 ? 255 : rgb[i], 1) << "HDR byte " << i;  // RGBE: 8-bit mantissas
  }
}

// Found by the image fuzzer (tests/fuzz/corpus/image/regression-jpeg-huffman-counts):
// a JPEG whose Huffman table counts more than 256 codes made stb_image
// write past its table. JPEG goes to libjpeg-turbo, which refuses it.
TEST(ImageDecode, AJpegWithTooManyHuffmanCodesIsRefused) {
  std::ifstream in(test::sourcePath("tests/fuzz/corpus/image/regression-jpeg-huffman-counts"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_TRUE(bytes.starts_with("\xff\xd8\xff"));
  EXPECT_NE(decodeError(bytes).find("t.png: not a readable JPEG image ("), std::string::npos) << decodeError(bytes);
}

TEST(ImageDecode, OtherFormatsNeverReachTheDecoder) {
  const char* expected = "t.png: not a PNG, BMP, JPEG, TGA, Radiance HDR or OpenEXR image";
  EXPECT_NE(decodeError("GIF89a\x01\x00\x01\x00").find(expected), std::string::npos);
  EXPECT_NE(decodeError(std::string("8BPS\0\1\0\0\0\0\0\0\0\3\0\0\0\1\0\0\0\1", 22)).find(expected),
            std::string::npos);                                                               // PSD
  EXPECT_NE(decodeError("P6\n1 1\n255\nabc").find(expected), std::string::npos);              // PNM
  EXPECT_NE(decodeError("\xff\xd8\xff\xe0 JFIF").find("not a readable"), std::string::npos);  // a JPEG cut short
}

// Found by the image fuzzer (tests/fuzz/corpus/image/regression-png-idat-claim):
// an 85-byte PNG whose second IDAT chunk claims 2 GB made stb_image reserve
// 2 GiB before reading it. Chunks are now checked against the file first.
TEST(ImageDecode, PngChunkLongerThanTheFileIsRefusedBeforeDecoding) {
  const std::string png(
      "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x04\x00\x00\x04\x03"
      "\x08\x02\x00\x00\x00\x3b\x96\x38\x91\x00\x00\x00\x1a\x49\x44\x41\x54\x78\x5e\x63\x0e\x0a\x00\x00"
      "\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x04\x00\x00\x00\x03\x08\x02\x00\xff\xff\x5f\x40\x00\x01\x7b"
      "\xb6\x00\x1a\x49\x44\x41\x54\x78\xfa\x4e\x44\xae\x42",
      85);
  const long before = peakVirtualKb();
  const std::string error = decodeError(png);
  EXPECT_NE(error.find("t.png: PNG chunk IDAT claims 2075525146 bytes, but only 2 follow"), std::string::npos) << error;
  EXPECT_LT(peakVirtualKb() - before, 256 * 1024) << "an 85-byte PNG reserved memory for what it claims";
}

// Found by the image fuzzer (corpus/image/regression-png-empty-idat): an
// empty IDAT chunk made stb_image memcpy into a null buffer.
TEST(ImageDecode, PngWithAnEmptyIdatIsRefused) {
  const std::string png(
      "\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR\x00\x00\x00\x04\x00\x00\x04\x03\x08\x02\x00\x00\x00\x3b\x96\x39"
      "\x91\x00\x00\x00\x00IDAT\xae\x42\x60\x82",
      45);
  EXPECT_NE(decodeError(png).find("t.png: PNG with an empty IDAT chunk is not supported"), std::string::npos)
      << decodeError(png);
}

// A BMP header announcing 4096 x 4096 pixels with no pixels after it: stb_image
// would allocate (and fill) 48 MiB for it.
TEST(ImageDecode, BmpShorterThanItsRowsIsRefusedBeforeDecoding) {
  const long before = peakVirtualKb();
  const std::string error = decodeError(test::bmp(4096, 4096, false));
  EXPECT_NE(error.find("BMP of 4096x4096 needs 50331702 bytes, the file has 54"), std::string::npos) << error;
  EXPECT_LT(peakVirtualKb() - before, 16 * 1024);
  SceneBudget budget;
  EXPECT_EQ(decodeImage(test::bmp(4, 2, true), "t.bmp", budget).rgb.size(), 24u);
}

// Found by the image fuzzer (corpus/image/regression-bmp-short-header): a BMP
// cut inside its header passed stb_image's header check, and the row check
// read past the end of the file.
TEST(ImageDecode, BmpCutInsideItsHeaderIsRefused) {
  const std::string cut = test::bmp(1, 1, true).substr(0, 27);
  EXPECT_NE(decodeError(cut).find("BMP header of 27 bytes (truncated)"), std::string::npos) << decodeError(cut);
}


// A Radiance header announcing 8192 x 8192 pixels, one run-length row after
// it: stb_image allocated 768 MiB of floats and filled the missing rows
// black. Rows are now walked as stb_image reads them, before it runs: a
// file written whole decodes (run-length rows here, flat rows in
// JpegTgaAndHdrDecodeToTheTexelsWritten's narrower image), one cut short
// anywhere is refused.
TEST(ImageDecode, ARadianceFileShorterThanItsRowsIsRefusedBeforeDecoding) {
  const std::string bomb = test::truncatedRadiance();
  const long before = peakVirtualKb();
  const std::string error = decodeError(bomb);
  EXPECT_NE(error.find("Radiance HDR image of 8192x8192 holds 1 of its rows"), std::string::npos) << error;
  EXPECT_LT(peakVirtualKb() - before, 16 * 1024);

  std::vector<float> linear(64 * 5 * 3, 0.5f);
  std::string hdr;
  ASSERT_NE(stbi_write_hdr_to_func(appendTo, &hdr, 64, 5, 3, linear.data()), 0);
  SceneBudget budget;
  EXPECT_EQ(decodeImage(hdr, "t.hdr", budget).rgb.size(), linear.size());
  for (const std::size_t cut : {std::size_t{1}, std::size_t{5}, std::size_t{30}}) {  // of 60 bytes of pixels
    const std::string error = decodeError(hdr.substr(0, hdr.size() - cut));
    EXPECT_NE(error.find("Radiance HDR image of 64x5 holds"), std::string::npos) << cut << ": " << error;
  }
}

// Each scan passes over the whole component: a file of 2,082 scans kept
// glintd's build busy for half a minute at 8192 x 8192. Up to kMaxJpegScans
// scans decode; one more is refused.
TEST(ImageDecode, AJpegOfTooManyScansIsRefused) {
  SceneBudget budget;
  const Image fine = decodeImage(test::progressiveJpeg(64, 0), "t.jpg", budget);  // 64 scans
  EXPECT_EQ(fine.rgb.size(), 64u * 64u * 3u);
  const std::string bomb = test::progressiveJpeg(64, 2);  // 190 scans
  const std::string error = decodeError(bomb);
  EXPECT_NE(error.find("t.png: not a readable JPEG image (more than " + std::to_string(kMaxJpegScans) + " scans)"),
            std::string::npos)
      << error;
}

// What each decoder holds while it decodes counts against the scene's limit
// before it is allocated, beside what the image keeps (3 bytes a texel),
// and is given back when it is done: stb_image's buffers (PNG, HDR's
// floats), libjpeg's coefficients of a progressive file. With room for the
// texels alone each is refused while it would decode; with room for both,
// the texels alone stay charged.
TEST(ImageDecode, DecodersBuffersAreChargedWhileTheyDecode) {
  constexpr int kSide = 64;
  std::vector<std::uint8_t> rgb(kSide * kSide * 3, 90);
  std::vector<float> linear(rgb.size(), 0.3f);
  std::string png, hdr;
  ASSERT_NE(stbi_write_png_to_func(appendTo, &png, kSide, kSide, 3, rgb.data(), kSide * 3), 0);
  ASSERT_NE(stbi_write_hdr_to_func(appendTo, &hdr, kSide, kSide, 3, linear.data()), 0);
  const std::size_t texels = std::size_t{kSide} * kSide * Image::kBytesPerTexel;
  for (const auto& [name, bytes] : {std::pair<const char*, std::string>{"png", png}, {"hdr", hdr},
                                    {"progressive jpeg", test::progressiveJpeg(kSide, 0)}}) {
    LoadLimits tight;
    tight.maxSceneBytes = texels;
    SceneBudget budget(tight);
    std::string error;
    try {
      decodeImage(bytes, "t", budget);
    } catch (const InputError& e) {
      error = e.what();
    }
    EXPECT_NE(error.find("t: the scene would hold"), std::string::npos) << name << ": " << error;
    EXPECT_NE(error.find("while it decodes"), std::string::npos) << name << ": " << error;
    SceneBudget roomy;
    EXPECT_EQ(decodeImage(bytes, "t", roomy).rgb.size(), rgb.size()) << name;
    EXPECT_EQ(roomy.used(), texels) << name;
  }
}

}  // namespace
}  // namespace glint
