#include "common/image/image_write.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <vector>

#include <stb_image_write.h>

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
