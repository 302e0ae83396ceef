#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "common/frame.h"
#include "common/linear_image.h"
#include "common/scene_budget.h"
#include "common/texture.h"

namespace glint {

// Decodes a PNG or 24-bit BMP held in memory into 8-bit RGB texels. The size
// its header gives is checked against the texture limit and charged to the
// budget before anything is decoded. Images wider or taller than their data,
// corrupt, or over a limit are rejected with an InputError that starts with
// `place`.
Image decodeImage(std::string_view bytes, const std::string& place, SceneBudget& budget);

// Encodes the frame as PNG and writes it atomically: to a temporary file
// beside `path`, renamed over it only once complete, so a failed or
// interrupted write never leaves a half-written image.
void writePng(const std::filesystem::path& path, const FrameImage& image);

// Writes `size` bytes to `path` atomically: to `path`.partial, renamed over
// `path` only once complete. Errors name the path.
void writeAtomically(const std::filesystem::path& path, const unsigned char* data, std::size_t size);

// Writes linear colour as a Portable Float Map (PF, little-endian, rows
// bottom-up as the format has them), atomically like writePng.
void writePfm(const std::filesystem::path& path, const LinearImage& image);

}  // namespace glint
