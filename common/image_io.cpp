#include "common/image_io.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <vector>

#include <stb_image.h>
#include <stb_image_write.h>

#include "common/error.h"

namespace glint {

Image decodeImage(std::string_view bytes, const std::string& place, SceneBudget& budget) {
  const std::size_t maxPixels = budget.limits().maxTexturePixels;
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw InputError(place + ": image file is too large");
  }
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

void writePng(const std::filesystem::path& path, const FrameImage& image) {
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
  std::filesystem::path tmp = path;
  tmp += ".partial";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw InputError(path.string() + ": cannot write (" + std::strerror(errno) +
                       "); check that the folder exists and is writable");
    }
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
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
    throw InputError(path.string() + ": cannot move the finished image into place (" + ec.message() + ")");
  }
}

}  // namespace glint
