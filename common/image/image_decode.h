#pragma once

#include <string>
#include <string_view>

#include "common/image/exr_decode.h"
#include "common/image/decode_budget.h"
#include "common/image/texel_image.h"

namespace glint {

// Decodes a PNG, BMP, JPEG, TGA, Radiance HDR or OpenEXR image held in
// memory into 8-bit RGB texels (an HDR or EXR image's linear values clamped
// to [0, 1]). The size its header gives is checked against the texture
// limit, and the file's structure against that size (image_checks.h), before
// anything is decoded; the budget is charged then with the texels the image
// keeps and the decoder's working buffers, which it holds until the decode
// returns. Images wider or taller than their data, corrupt, or over a limit
// are rejected with an InputError that starts with `place`.
Image decodeImage(std::string_view bytes, const std::string& place, DecodeBudget& budget);

// Whether the bytes start as a Radiance HDR file does.
bool looksLikeRadiance(std::string_view bytes);

// Decodes a Radiance HDR or OpenEXR image into its linear RGB floats as the
// file holds them (an environment's light: nothing clamped), under the same
// checks, its floats charged to the budget. Any other format is an
// InputError starting with `place`.
FloatPixels decodeLinearImage(std::string_view bytes, const std::string& place, DecodeBudget& budget);

}  // namespace glint
