#include "common/scene/image_decode.h"

#include <limits>
#include <memory>
#include <vector>

#include <stb_image.h>

#include "common/base/error.h"

namespace glint {
namespace {

std::uint32_t bigEndian32(std::string_view b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) << 24 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 3]));
}

std::uint32_t littleEndian(std::string_view b, std::size_t at, int bytes) {
  std::uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
  return v;
}

// Every chunk of a PNG must lie within the file: stb_image grows its buffer
// by the length a chunk claims before reading it (the image fuzzer found a
// 100-byte PNG that made it allocate 2 GiB).
void checkPngChunks(std::string_view bytes, const std::string& place) {
  constexpr std::size_t kChunkOverhead = 12;  // length, type, CRC
  for (std::size_t at = 8; at + 8 <= bytes.size();) {
    const std::uint32_t length = bigEndian32(bytes, at);
    const std::size_t left = bytes.size() - at < kChunkOverhead ? 0 : bytes.size() - at - kChunkOverhead;
    const std::string type(bytes.substr(at + 4, 4));
    if (length > left) {
      throw InputError(place + ": PNG chunk " + type + " claims " + std::to_string(length) + " bytes, but only " +
                       std::to_string(left) + " follow (truncated or corrupt)");
    }
    // stb_image copies an empty IDAT into a buffer it has not allocated yet
    // (memcpy to null: undefined behaviour, found by the image fuzzer).
    if (type == "IDAT" && length == 0) {
      throw InputError(place + ": PNG with an empty IDAT chunk is not supported (save it again with any PNG encoder)");
    }
    if (type == "IEND") return;
    at += kChunkOverhead + length;
  }
}

// An uncompressed BMP must hold the rows its header announces: stb_image
// allocates the whole image before it reads them.
void checkBmpRows(std::string_view bytes, int width, int height, const std::string& place) {
  constexpr std::size_t kHeaderBytes = 30;  // up to the bits per pixel
  if (bytes.size() < kHeaderBytes) {
    throw InputError(place + ": BMP header of " + std::to_string(bytes.size()) + " bytes (truncated)");
  }
  const std::uint32_t offset = littleEndian(bytes, 10, 4);
  const std::uint32_t bitsPerPixel = littleEndian(bytes, 28, 2);
  const std::size_t rowBytes = (static_cast<std::size_t>(width) * bitsPerPixel + 31) / 32 * 4;
  const std::size_t needed = offset + rowBytes * static_cast<std::size_t>(height);
  if (bytes.size() < needed) {
    throw InputError(place + ": BMP of " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                     std::to_string(needed) + " bytes, the file has " + std::to_string(bytes.size()) +
                     " (truncated)");
  }
}

}  // namespace

Image decodeImage(std::string_view bytes, const std::string& place, SceneBudget& budget) {
  const std::size_t maxPixels = budget.limits().maxTexturePixels;
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw InputError(place + ": image file is too large");
  }
  // Only the formats the scene format names reach stb_image: it would try a
  // dozen others (JPEG, GIF, PSD ...) on bytes a client sent.
  const bool png = bytes.starts_with("\x89PNG\r\n\x1a\n");
  if (!png && !bytes.starts_with("BM")) throw InputError(place + ": not a PNG or BMP image");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(data, size, &w, &h, &channels)) {
    throw InputError(place + ": not a readable PNG or BMP image (" + stbi_failure_reason() + ")");
  }
  if (w <= 0 || h <= 0 || static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > maxPixels) {
    throw InputError(place + ": image of " + std::to_string(w) + "x" + std::to_string(h) +
                     " pixels is over the limit of " + std::to_string(maxPixels) + " pixels");
  }
  budget.chargeImage(w, h, place);
  if (png) {
    checkPngChunks(bytes, place);
  } else {
    checkBmpRows(bytes, w, h, place);
  }
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(data, size, &w, &h, &channels, 3),
                                                   stbi_image_free);
  if (!pixels) {
    throw InputError(place + ": cannot decode image (" + stbi_failure_reason() + ")");
  }
  Image image;
  image.width = w;
  image.height = h;
  image.rgb.assign(pixels.get(), pixels.get() + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
  return image;
}

}  // namespace glint
