#pragma once

#include <array>
#include <string_view>
#include <utility>

#include "common/base/enum_words.h"

namespace glint {

// How linear colour becomes an 8-bit value: kLinear stores it as it is (the
// thesis's frame buffer), kSrgb applies the sRGB transfer function.
enum class Encoding { kLinear, kSrgb };

template <>
struct EnumWords<Encoding> {
  static constexpr std::array<std::pair<Encoding, std::string_view>, 2> kWords{
      {{Encoding::kLinear, "linear"}, {Encoding::kSrgb, "srgb"}}};
};

// What a frame's colour becomes in its output: scaled by 2^exposure (EV),
// then, for 8-bit values, encoded (common/image/encoding.h). sRGB unless a
// scene says otherwise: a PNG is shown through a display's sRGB response,
// and assets (glTF's colours and textures) are authored for it; the thesis's
// scenes in scenes/ name the linear frame buffer they were made for.
struct OutputSettings {
  Encoding encoding = Encoding::kSrgb;
  float exposure = 0.0f;
};

}  // namespace glint
