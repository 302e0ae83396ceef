#include "common/scene/image_decode.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <stb_image.h>

#include "common/base/error.h"
#include "common/scene/exr_decode.h"
#include "common/scene/jpeg_decode.h"

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
                     std::to_string(needed) + " bytes, the file has " + std::to_string(bytes.size()) + " (truncated)");
  }
}

// The formats textures are read in, told apart by their first bytes. TGA
// has no signature: its header's colour-map type (0 or 1), image type and
// bits per pixel must be ones TGA defines, which no other format's first
// bytes are.
enum class ImageFormat { kPng, kBmp, kJpeg, kTga, kHdr, kExr };
constexpr const char* kFormats = "PNG, BMP, JPEG, TGA, Radiance HDR or OpenEXR";

bool looksLikeTga(std::string_view b) {
  constexpr std::size_t kHeaderBytes = 18;
  if (b.size() < kHeaderBytes) return false;
  const auto byte = [&b](std::size_t i) { return static_cast<unsigned char>(b[i]); };
  const bool colourMap = byte(1) <= 1;
  const bool imageType = byte(2) == 1 || byte(2) == 2 || byte(2) == 3 || byte(2) == 9 || byte(2) == 10 || byte(2) == 11;
  const unsigned bits = byte(16);
  return colourMap && imageType && (bits == 8 || bits == 15 || bits == 16 || bits == 24 || bits == 32);
}

std::optional<ImageFormat> imageFormat(std::string_view b) {
  if (b.starts_with("\x89PNG\r\n\x1a\n")) return ImageFormat::kPng;
  if (b.starts_with("BM")) return ImageFormat::kBmp;
  if (b.starts_with("\xff\xd8\xff")) return ImageFormat::kJpeg;
  if (looksLikeRadiance(b)) return ImageFormat::kHdr;
  if (looksLikeExr(b)) return ImageFormat::kExr;
  if (looksLikeTga(b)) return ImageFormat::kTga;
  return std::nullopt;
}

using StbPixels = std::unique_ptr<void, void (*)(void*)>;

// 8-bit RGB as the file holds it.
Image decode8Bit(const stbi_uc* data, int size, const std::string& place) {
  int w = 0, h = 0, channels = 0;
  const StbPixels pixels(stbi_load_from_memory(data, size, &w, &h, &channels, 3), stbi_image_free);
  if (!pixels) throw InputError(place + ": cannot decode image (" + stbi_failure_reason() + ")");
  const auto* rgb = static_cast<const std::uint8_t*>(pixels.get());
  return {w, h, std::vector<std::uint8_t>(rgb, rgb + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3)};
}

// Radiance HDR's linear floats as the file holds them.
FloatPixels hdrFloats(const stbi_uc* data, int size, const std::string& place) {
  int w = 0, h = 0, channels = 0;
  const StbPixels pixels(stbi_loadf_from_memory(data, size, &w, &h, &channels, 3), stbi_image_free);
  if (!pixels) throw InputError(place + ": cannot decode image (" + stbi_failure_reason() + ")");
  const auto* linear = static_cast<const float*>(pixels.get());
  return {w, h, std::vector<float>(linear, linear + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3)};
}

// The same as 8-bit texels (byte / 255, as every texture reads): values
// above 1 are clamped, since textures are 8-bit.
Image decodeHdr(const stbi_uc* data, int size, const std::string& place) {
  const FloatPixels linear = hdrFloats(data, size, place);
  Image image{linear.width, linear.height, std::vector<std::uint8_t>(linear.rgb.size())};
  std::transform(linear.rgb.begin(), linear.rgb.end(), image.rgb.begin(), linearTexelByte);
  return image;
}

// Checks the size a header gives against the texture limit and charges it
// to the budget (bytesPerTexel each), before anything is decoded.
std::function<void(int, int)> admitter(SceneBudget& budget, const std::string& place, std::size_t bytesPerTexel) {
  return [&budget, &place, bytesPerTexel](int w, int h) {
    const std::size_t maxPixels = budget.limits().maxTexturePixels;
    if (w <= 0 || h <= 0 || static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > maxPixels) {
      throw InputError(place + ": image of " + std::to_string(w) + "x" + std::to_string(h) +
                       " pixels is over the limit of " + std::to_string(maxPixels) + " pixels");
    }
    budget.chargeImage(w, h, place, bytesPerTexel);
  };
}

void checkDecodable(std::string_view bytes, const std::string& place) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw InputError(place + ": image file is too large");
  }
}

// The size stb_image reads in a header, admitted.
void admitStb(std::string_view bytes, const std::function<void(int, int)>& admit, int& w, int& h,
              const std::string& place) {
  int channels = 0;
  if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()), &w, &h,
                             &channels)) {
    throw InputError(place + ": not a readable " + kFormats + " image (" + stbi_failure_reason() + ")");
  }
  admit(w, h);
}

}  // namespace

bool looksLikeRadiance(std::string_view bytes) {
  return bytes.starts_with("#?RADIANCE") || bytes.starts_with("#?RGBE");
}

Image decodeImage(std::string_view bytes, const std::string& place, SceneBudget& budget) {
  checkDecodable(bytes, place);
  // Only the formats read here reach a decoder (stb_image would try others:
  // GIF, PSD, PIC, PNM); JPEG goes to libjpeg-turbo (jpeg_decode.h) and
  // OpenEXR to OpenEXR's core library (exr_decode.h).
  const std::optional<ImageFormat> format = imageFormat(bytes);
  if (!format) throw InputError(place + ": not a " + kFormats + " image");
  const auto admit = admitter(budget, place, SceneBudget::kBytesPerTexel);
  if (*format == ImageFormat::kJpeg) return decodeJpeg(bytes, place, admit);
  if (*format == ImageFormat::kExr) return decodeExr(bytes, place, admit);
  int w = 0, h = 0;
  admitStb(bytes, admit, w, h, place);
  if (*format == ImageFormat::kPng) checkPngChunks(bytes, place);
  if (*format == ImageFormat::kBmp) checkBmpRows(bytes, w, h, place);
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  Image image = *format == ImageFormat::kHdr ? decodeHdr(data, size, place) : decode8Bit(data, size, place);
  if (image.width != w || image.height != h) throw InputError(place + ": the image's size changed while decoding");
  return image;
}

FloatPixels decodeLinearImage(std::string_view bytes, const std::string& place, SceneBudget& budget) {
  checkDecodable(bytes, place);
  const std::optional<ImageFormat> format = imageFormat(bytes);
  if (format != ImageFormat::kHdr && format != ImageFormat::kExr) {
    throw InputError(place + ": not a Radiance HDR or OpenEXR image (an environment's values are linear light; "
                             "convert an 8-bit image to one of these)");
  }
  const auto admit = admitter(budget, place, SceneBudget::kBytesPerFloatTexel);
  if (*format == ImageFormat::kExr) return decodeExrLinear(bytes, place, admit);
  int w = 0, h = 0;
  admitStb(bytes, admit, w, h, place);
  FloatPixels pixels = hdrFloats(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()), place);
  if (pixels.width != w || pixels.height != h) throw InputError(place + ": the image's size changed while decoding");
  return pixels;
}

}  // namespace glint
