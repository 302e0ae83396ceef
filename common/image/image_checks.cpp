#include "common/image/image_checks.h"

#include <cstdint>
#include <optional>

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

// Where a Radiance file's pixels start: after the header's empty line and
// the resolution line that follows it (none: the header is cut short).
std::optional<std::size_t> radianceData(std::string_view bytes) {
  const std::size_t headerEnd = bytes.find("\n\n");
  if (headerEnd == std::string_view::npos) return std::nullopt;
  const std::size_t lineEnd = bytes.find('\n', headerEnd + 2);
  if (lineEnd == std::string_view::npos) return std::nullopt;
  return lineEnd + 1;
}

// The bytes one run-length encoded channel of a row takes from `at`, or
// none if the file ends (or a run overflows the row: stb_image refuses it).
std::optional<std::size_t> radianceChannel(std::string_view bytes, std::size_t at, int width) {
  const std::size_t start = at;
  for (int filled = 0; filled < width;) {
    if (at >= bytes.size()) return std::nullopt;
    const int count = static_cast<unsigned char>(bytes[at++]);
    const int run = count > 128 ? count - 128 : count;
    if (run == 0 || run > width - filled) return std::nullopt;
    at += count > 128 ? 1 : static_cast<std::size_t>(run);
    filled += run;
  }
  if (at > bytes.size()) return std::nullopt;
  return at - start;
}

}  // namespace

// The image fuzzer found a 100-byte PNG that made stb_image allocate 2 GiB.
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
                     std::to_string(needed) + " bytes, the file has " + std::to_string(bytes.size()) + " (truncated)");
  }
}

void checkRadianceRows(std::string_view bytes, int width, int height, const std::string& place) {
  // stb_image reads rows narrower than 8 or wider than 32767 flat.
  constexpr int kMinRunWidth = 8, kMaxRunWidth = 32767;
  const std::optional<std::size_t> data = radianceData(bytes);
  const auto truncated = [&](int rows) {
    return InputError(place + ": Radiance HDR image of " + std::to_string(width) + "x" + std::to_string(height) +
                      " holds " + std::to_string(rows) + " of its rows (truncated or corrupt)");
  };
  if (!data) throw truncated(0);
  const std::size_t flatBytes = std::size_t{4} * static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const bool runs = width >= kMinRunWidth && width <= kMaxRunWidth;
  std::size_t at = *data;
  for (int row = 0; row < height; ++row) {
    if (bytes.size() - at < 4) throw truncated(row);
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(bytes[at + i]); };
    if (!runs || byte(0) != 2 || byte(1) != 2 || (byte(2) & 0x80) != 0) {
      // Not a run-length row: stb_image reads the whole image flat from here.
      if (bytes.size() - at < flatBytes) throw truncated(row);
      return;
    }
    at += 4;
    for (int channel = 0; channel < 4; ++channel) {
      const std::optional<std::size_t> used = radianceChannel(bytes, at, width);
      if (!used) throw truncated(row);
      at += *used;
    }
  }
}

}  // namespace glint
