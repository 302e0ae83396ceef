#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "common/scene/texture.h"

namespace glint {

// Decodes a baseline or progressive JPEG held in memory into 8-bit RGB
// texels with libjpeg-turbo (stb_image's JPEG decoder writes out of bounds
// on bad Huffman tables, and these bytes may come from any client).
// `admit(width, height)` sees the header's size before anything is decoded
// and throws to refuse it. Corrupt data, warnings included, is an
// InputError starting with `place`.
Image decodeJpeg(std::string_view bytes, const std::string& place, const std::function<void(int, int)>& admit);

}  // namespace glint
