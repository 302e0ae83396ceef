#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "common/scene/texture.h"

namespace glint {

// Whether the bytes start with OpenEXR's magic number.
bool looksLikeExr(std::string_view bytes);

// Decodes a single-part, flat (not deep) OpenEXR image held in memory, its
// scanlines or its tiles' first level, into 8-bit RGB texels: R, G and B
// (or Y for all three), linear, clamped to [0, 1] as every texture reads.
// OpenEXR's core library reads it (the C library written to face hostile
// files, with its own size checks); `admit(width, height)` sees the data
// window's size before any pixel is read and throws to refuse it. Corrupt
// data, missing colour channels or subsampled channels are an InputError
// starting with `place`.
Image decodeExr(std::string_view bytes, const std::string& place, const std::function<void(int, int)>& admit);

}  // namespace glint
