#include "common/image/image_write.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

#include <stb_image_write.h>
#include <zlib.h>

#include "common/base/error.h"

namespace glint {

void writeAtomically(const std::filesystem::path& path, const unsigned char* data, std::size_t size) {
  std::filesystem::path tmp = path;
  tmp += ".partial";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw InputError(path.string() + ": cannot write (" + std::strerror(errno) +
                       "); check that the folder exists and is writable");
    }
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw InputError(path.string() + ": write failed (" + std::strerror(errno) + ")");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(path.string() + ": cannot move the finished file into place (" + ec.message() + ")");
  }
}

namespace {

void appendBigEndian(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<unsigned char>(v >> shift));
}

// One PNG chunk: its length, type, data and the CRC of type and data.
void appendChunk(std::vector<unsigned char>& out, const char type[4], const std::vector<std::uint32_t>& words,
                 const std::vector<unsigned char>& bytes = {}) {
  std::vector<unsigned char> body(type, type + 4);
  for (std::uint32_t w : words) appendBigEndian(body, w);
  body.insert(body.end(), bytes.begin(), bytes.end());
  appendBigEndian(out, static_cast<std::uint32_t>(body.size() - 4));
  out.insert(out.end(), body.begin(), body.end());
  appendBigEndian(out, static_cast<std::uint32_t>(crc32(0L, body.data(), static_cast<uInt>(body.size()))));
}

// The chunks that say how the values hold light (PNG 3rd edition, 11.3.2):
// gAMA is 100000 x the decoding exponent's inverse, cHRM the sRGB (Rec. 709)
// white point and primaries x 100000.
std::vector<unsigned char> colourChunks(Encoding encoding) {
  std::vector<unsigned char> chunks;
  if (encoding == Encoding::kSrgb) appendChunk(chunks, "sRGB", {}, {0});  // rendering intent: perceptual
  appendChunk(chunks, "gAMA", {encoding == Encoding::kSrgb ? 45455u : 100000u});
  appendChunk(chunks, "cHRM", {31270, 32900, 64000, 33000, 30000, 60000, 15000, 6000});
  return chunks;
}

}  // namespace

void writePng(const std::filesystem::path& path, const FrameImage& image, Encoding encoding) {
  std::vector<unsigned char> png;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* bytes = static_cast<const unsigned char*>(data);
    out->insert(out->end(), bytes, bytes + size);
  };
  if (!stbi_write_png_to_func(append, &png, image.width, image.height, 3, image.rgb.data(),
                              image.width * 3)) {
    throw InputError(path.string() + ": PNG encoding failed");
  }
  constexpr std::size_t kAfterHeader = 8 + 25;  // the signature, then IHDR (12 bytes of frame, 13 of data)
  const std::vector<unsigned char> chunks = colourChunks(encoding);
  png.insert(png.begin() + kAfterHeader, chunks.begin(), chunks.end());
  writeAtomically(path, png.data(), png.size());
}

void writePfm(const std::filesystem::path& path, const LinearImage& image) {
  const std::string header = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  std::vector<unsigned char> pfm(header.begin(), header.end());
  const std::size_t rowFloats = static_cast<std::size_t>(image.width) * 3;
  for (int y = image.height - 1; y >= 0; --y) {  // PFM rows run bottom-up
    const auto* row = reinterpret_cast<const unsigned char*>(&image.rgb[static_cast<std::size_t>(y) * rowFloats]);
    pfm.insert(pfm.end(), row, row + rowFloats * sizeof(float));  // little-endian, as "-1.0" says
  }
  writeAtomically(path, pfm.data(), pfm.size());
}

}  // namespace glint
