#pragma once

#include <string>
#include <string_view>

#include "common/image/decode_admit.h"
#include "common/image/texel_image.h"

namespace glint {

// Decodes a baseline or progressive JPEG held in memory into 8-bit RGB
// texels with libjpeg-turbo (stb_image's JPEG decoder writes out of bounds
// on bad Huffman tables, and these bytes may come from any client).
// `admit` sees the header's size and, for a progressive or multi-scan file,
// the coefficients libjpeg holds for the whole image, before anything is
// decoded. A file of more than kMaxJpegScans scans is refused (each scan
// passes over a whole component: 2,000 scans of 8192 x 8192 took half a
// minute). Corrupt data, warnings included, is an InputError starting with
// `place`.
Image decodeJpeg(std::string_view bytes, const std::string& place, const DecodeAdmit& admit);

// The most scans a JPEG may have. The standard progressive scripts use 10
// for a colour image (libjpeg's jpeg_simple_progression); decoders facing
// hostile files bound them likewise (NVIDIA's nvImageCodec: 256).
constexpr int kMaxJpegScans = 128;

}  // namespace glint
