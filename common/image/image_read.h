#pragma once

#include <filesystem>

#include "common/image/linear_image.h"

namespace glint {

// An image file's pixels as the file holds them: an 8-bit file's values / 255
// (what a display is sent), a float file's linear values.
struct ImageFile {
  LinearImage values;
  bool eightBit = false;
};

// Reads a PNG, JPEG, BMP or TGA (8 bits), or an OpenEXR, a PFM or a
// Radiance HDR (linear floats, as the file holds them) of at most
// LoadLimits' texture size. Throws InputError naming the file and what
// is wrong with it.
ImageFile readImageFile(const std::filesystem::path& path);

// The light a display shows for the file: an 8-bit file's values decoded by
// sRGB, a float file's values as they are (clamped to [0, 1] by whoever
// needs display values).
LinearImage displayedLight(const ImageFile& file);

}  // namespace glint
