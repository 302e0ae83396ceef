#pragma once

#include <cstddef>
#include <filesystem>

#include "common/image/frame_image.h"
#include "common/image/linear_image.h"
#include "common/image/output_settings.h"

namespace glint {

// Encodes the frame as PNG and writes it atomically: to a temporary file
// beside `path`, renamed over it only once complete, so a failed or
// interrupted write never leaves a half-written image. The file says how
// its values hold light, so that viewers show it right: sRGB values carry
// an sRGB chunk (with the gAMA and cHRM the PNG specification pairs with
// it), linear ones gAMA 1.0 and the sRGB primaries.
void writePng(const std::filesystem::path& path, const FrameImage& image, Encoding encoding);

// Writes `size` bytes to `path` atomically: to `path`.partial, renamed over
// `path` only once complete. Errors name the path.
void writeAtomically(const std::filesystem::path& path, const unsigned char* data, std::size_t size);

// Writes linear colour as a Portable Float Map (PF, little-endian, rows
// bottom-up as the format has them), atomically like writePng.
void writePfm(const std::filesystem::path& path, const LinearImage& image);

}  // namespace glint
