#include "common/image/image_read.h"

#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "common/base/error.h"
#include "common/base/file_source.h"
#include "common/image/decode_budget.h"
#include "common/image/encoding.h"
#include "common/image/exr_decode.h"
#include "common/image/image_decode.h"

namespace glint {
namespace {

std::string readBytes(const std::filesystem::path& path, std::size_t maxBytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open the image (check the path)");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size > maxBytes) {
    throw InputError(path.string() + ": not a readable image file of at most " + std::to_string(maxBytes >> 20) +
                     " MiB");
  }
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return std::move(bytes).str();
}

void admitSize(const std::string& place, int width, int height, std::size_t maxPixels) {
  if (width <= 0 || height <= 0 || static_cast<std::size_t>(width) * static_cast<std::size_t>(height) > maxPixels) {
    throw InputError(place + ": image of " + std::to_string(width) + "x" + std::to_string(height) +
                     " pixels is empty or over the limit of " + std::to_string(maxPixels) + " pixels");
  }
}

// The header's next whitespace-separated word, from `at` on.
std::string_view nextWord(std::string_view bytes, std::size_t& at) {
  while (at < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
  const std::size_t from = at;
  while (at < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
  return bytes.substr(from, at - from);
}

// PFM: "PF" (RGB) or "Pf" (grey), width, height, a scale whose sign is the
// byte order (negative: little-endian), one whitespace byte, then rows of
// floats from the bottom up.
LinearImage decodePfm(std::string_view bytes, const std::string& place, std::size_t maxPixels) {
  std::size_t at = 0;
  const std::string_view magic = nextWord(bytes, at);
  const int channels = magic == "PF" ? 3 : 1;
  int width = 0, height = 0;
  const std::string_view w = nextWord(bytes, at), h = nextWord(bytes, at), scale = nextWord(bytes, at);
  if (std::from_chars(w.data(), w.data() + w.size(), width).ec != std::errc{} ||
      std::from_chars(h.data(), h.data() + h.size(), height).ec != std::errc{} || scale.empty()) {
    throw InputError(place + ": not a PFM image (its header is not 'PF', width, height, scale)");
  }
  admitSize(place, width, height, maxPixels);
  if (!scale.starts_with('-')) throw InputError(place + ": big-endian PFM images are not read; write it little-endian");
  ++at;  // the single whitespace byte after the scale
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * channels;
  if (bytes.size() < at || bytes.size() - at < count * sizeof(float)) {
    throw InputError(place + ": PFM image is shorter than its " + std::to_string(width) + "x" +
                     std::to_string(height) + " pixels");
  }
  LinearImage image{width, height, std::vector<float>(static_cast<std::size_t>(width) * height * 3)};
  for (std::size_t i = 0; i < count / channels; ++i) {
    const std::size_t row = i / width, column = i % width;
    const std::size_t to = ((height - 1 - row) * width + column) * 3;
    for (int k = 0; k < 3; ++k) {
      std::memcpy(&image.rgb[to + k], bytes.data() + at + (i * channels + (channels == 3 ? k : 0)) * sizeof(float),
                  sizeof(float));
    }
  }
  return image;
}

}  // namespace

ImageFile readImageFile(const std::filesystem::path& path) {
  const std::string place = path.string();
  const std::string bytes = readBytes(path, kDefaultMaxFileBytes);
  PixelLimit limit(kDefaultMaxTexturePixels);
  const auto admit = [&](int width, int height, std::size_t) {
    admitSize(place, width, height, limit.maxTexturePixels());
  };
  if (looksLikeExr(bytes)) {
    FloatPixels pixels = decodeExrLinear(bytes, place, admit);
    return {{pixels.width, pixels.height, std::move(pixels.rgb)}, false};
  }
  if (bytes.starts_with("PF") || bytes.starts_with("Pf")) return {decodePfm(bytes, place, limit.maxTexturePixels()), false};
  if (looksLikeRadiance(bytes)) {
    FloatPixels pixels = decodeLinearImage(bytes, place, limit);
    return {{pixels.width, pixels.height, std::move(pixels.rgb)}, false};
  }
  const Image decoded = decodeImage(bytes, place, limit);
  LinearImage values{decoded.width, decoded.height, std::vector<float>(decoded.rgb.size())};
  for (std::size_t i = 0; i < decoded.rgb.size(); ++i) values.rgb[i] = static_cast<float>(decoded.rgb[i]) / 255.0f;
  return {std::move(values), true};
}

LinearImage displayedLight(const ImageFile& file) {
  LinearImage light = file.values;
  if (file.eightBit) {
    for (float& v : light.rgb) v = srgbDecode(v);
  }
  return light;
}

}  // namespace glint
