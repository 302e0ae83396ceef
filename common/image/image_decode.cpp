#include "common/image/image_decode.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <stb_image.h>

#include "common/base/error.h"
#include "common/image/exr_decode.h"
#include "common/image/image_checks.h"
#include "common/image/jpeg_decode.h"

namespace glint {
namespace {

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

// Radiance HDR's float RGB as stb_image decodes it (w x h x 3).
StbPixels stbFloats(const stbi_uc* data, int size, const std::string& place, int& w, int& h) {
  int channels = 0;
  StbPixels pixels(stbi_loadf_from_memory(data, size, &w, &h, &channels, 3), stbi_image_free);
  if (!pixels) throw InputError(place + ": cannot decode image (" + stbi_failure_reason() + ")");
  return pixels;
}

// Radiance HDR's linear floats as the file holds them.
FloatPixels hdrFloats(const stbi_uc* data, int size, const std::string& place) {
  int w = 0, h = 0;
  const StbPixels pixels = stbFloats(data, size, place, w, h);
  const auto* linear = static_cast<const float*>(pixels.get());
  return {w, h, std::vector<float>(linear, linear + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3)};
}

// The same as 8-bit texels (byte / 255, as every texture reads): values
// above 1 are clamped, since textures are 8-bit.
Image decodeHdr(const stbi_uc* data, int size, const std::string& place) {
  int w = 0, h = 0;
  const StbPixels pixels = stbFloats(data, size, place, w, h);
  const auto* linear = static_cast<const float*>(pixels.get());
  Image image{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3)};
  std::transform(linear, linear + image.rgb.size(), image.rgb.begin(), linearTexelByte);
  return image;
}

// The most stb_image holds at once while it decodes an image of `channels`
// channels (as its header says), a texel: BMP and TGA their pixels and the
// RGB they are converted to; PNG its inflated rows beside its pixels (twice
// as large at 16 bits a sample), then 16-bit pixels beside their 8-bit
// ones, then pixels beside their RGB (where they are not RGB already);
// Radiance HDR its float RGB.
std::size_t stbHeldBytesPerTexel(ImageFormat format, std::string_view bytes, int channels) {
  constexpr std::size_t kRgb = 3;
  const auto c = static_cast<std::size_t>(std::max(channels, 0));
  if (format == ImageFormat::kHdr) return 3 * sizeof(float);
  if (format != ImageFormat::kPng) return c + kRgb;
  const bool wide = stbi_is_16_bit_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()),
                                               static_cast<int>(bytes.size())) != 0;
  const std::size_t inflated = 2 * c * (wide ? 2 : 1);
  const std::size_t narrowed = wide ? 3 * c : 0;
  const std::size_t toRgb = c != kRgb ? c + kRgb : 0;
  return std::max({inflated, narrowed, toRgb});
}

// Checks the size a header gives against the texture limit and charges the
// budget before anything is decoded: the texels the image keeps
// (keptPerTexel bytes each), then the decoder's working buffers, held until
// the Admission ends with the decode.
class Admission {
 public:
  Admission(DecodeBudget& budget, const std::string& place, std::size_t keptPerTexel)
      : budget_(budget), place_(place), keptPerTexel_(keptPerTexel) {}
  ~Admission() { budget_.refund(held_); }
  Admission(const Admission&) = delete;
  Admission& operator=(const Admission&) = delete;

  void admit(int w, int h) {
    const std::size_t maxPixels = budget_.maxTexturePixels();
    if (w <= 0 || h <= 0 || static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > maxPixels) {
      throw InputError(place_ + ": image of " + std::to_string(w) + "x" + std::to_string(h) +
                       " pixels is over the limit of " + std::to_string(maxPixels) + " pixels");
    }
    budget_.chargeImage(w, h, place_, keptPerTexel_);
  }
  void hold(std::size_t bytes) {
    budget_.charge(bytes, place_, "while it decodes");
    held_ += bytes;
  }
  DecodeAdmit callback() {
    return [this](int w, int h, std::size_t heldBytes) {
      admit(w, h);
      hold(heldBytes);
    };
  }

 private:
  DecodeBudget& budget_;
  const std::string& place_;
  std::size_t keptPerTexel_;
  std::size_t held_ = 0;
};

void checkDecodable(std::string_view bytes, const std::string& place) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw InputError(place + ": image file is too large");
  }
}

// The size stb_image reads in a header, admitted; then the file's structure
// checked against it (image_checks.h) and stb_image's buffers held.
void admitStb(std::string_view bytes, ImageFormat format, Admission& admission, int& w, int& h,
              const std::string& place) {
  int channels = 0;
  if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()), &w, &h,
                             &channels)) {
    throw InputError(place + ": not a readable " + kFormats + " image (" + stbi_failure_reason() + ")");
  }
  admission.admit(w, h);
  if (format == ImageFormat::kPng) checkPngChunks(bytes, place);
  if (format == ImageFormat::kBmp) checkBmpRows(bytes, w, h, place);
  if (format == ImageFormat::kHdr) checkRadianceRows(bytes, w, h, place);
  admission.hold(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) *
                 stbHeldBytesPerTexel(format, bytes, channels));
}

}  // namespace

bool looksLikeRadiance(std::string_view bytes) {
  return bytes.starts_with("#?RADIANCE") || bytes.starts_with("#?RGBE");
}

Image decodeImage(std::string_view bytes, const std::string& place, DecodeBudget& budget) {
  checkDecodable(bytes, place);
  // Only the formats read here reach a decoder (stb_image would try others:
  // GIF, PSD, PIC, PNM); JPEG goes to libjpeg-turbo (jpeg_decode.h) and
  // OpenEXR to OpenEXR's core library (exr_decode.h).
  const std::optional<ImageFormat> format = imageFormat(bytes);
  if (!format) throw InputError(place + ": not a " + kFormats + " image");
  Admission admission(budget, place, Image::kBytesPerTexel);
  if (*format == ImageFormat::kJpeg) return decodeJpeg(bytes, place, admission.callback());
  if (*format == ImageFormat::kExr) return decodeExr(bytes, place, admission.callback());
  int w = 0, h = 0;
  admitStb(bytes, *format, admission, w, h, place);
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  Image image = *format == ImageFormat::kHdr ? decodeHdr(data, size, place) : decode8Bit(data, size, place);
  if (image.width != w || image.height != h) throw InputError(place + ": the image's size changed while decoding");
  return image;
}

FloatPixels decodeLinearImage(std::string_view bytes, const std::string& place, DecodeBudget& budget) {
  checkDecodable(bytes, place);
  const std::optional<ImageFormat> format = imageFormat(bytes);
  if (format != ImageFormat::kHdr && format != ImageFormat::kExr) {
    throw InputError(place +
                     ": not a Radiance HDR or OpenEXR image (an environment's values are linear light; "
                     "convert an 8-bit image to one of these)");
  }
  Admission admission(budget, place, FloatPixels::kBytesPerTexel);
  if (*format == ImageFormat::kExr) return decodeExrLinear(bytes, place, admission.callback());
  int w = 0, h = 0;
  admitStb(bytes, *format, admission, w, h, place);
  FloatPixels pixels = hdrFloats(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()), place);
  if (pixels.width != w || pixels.height != h) throw InputError(place + ": the image's size changed while decoding");
  return pixels;
}

}  // namespace glint
