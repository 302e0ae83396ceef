#pragma once

#include <string>
#include <string_view>

#include "common/image/decode_admit.h"
#include "common/image/texel_image.h"

namespace glint {

// Whether the bytes start with OpenEXR's magic number.
bool looksLikeExr(std::string_view bytes);

// Decodes a single-part, flat (not deep) OpenEXR image held in memory, its
// scanlines or its tiles' first level, into its linear R, G and B (or Y for
// all three) as floats.
// OpenEXR's core library reads it (the C library written to face hostile
// files, with its own size checks); `admit` sees the data window's size and
// the largest chunk's buffers once the chunks are checked against the file,
// before any pixel is read or the image allocated. Corrupt
// data, missing colour channels or subsampled channels are an InputError
// starting with `place`.
FloatPixels decodeExrLinear(std::string_view bytes, const std::string& place, const DecodeAdmit& admit);

// The same image as 8-bit texels, clamped to [0, 1] as every texture reads
// (each sample converted as it is read: no float image is held).
Image decodeExr(std::string_view bytes, const std::string& place, const DecodeAdmit& admit);

}  // namespace glint
