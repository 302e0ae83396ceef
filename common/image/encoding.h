#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "common/image/frame_image.h"
#include "common/image/linear_image.h"
#include "common/image/output_settings.h"

namespace glint {

// Linear colour -> output values, as OutputSettings say: multiplied by
// 2^exposure, then (8-bit outputs only) the transfer function. With the
// defaults (linear, 0 EV) a value passes unchanged, so 8-bit values are the
// thesis's frame buffer. The raster shaders apply the same formulas
// (client/raster/raster_shaders.cpp, encodeOutput).
class Encoder {
 public:
  explicit Encoder(const OutputSettings& output);

  // The value a float output (.exr, .pfm) holds: scaled, not encoded.
  glm::vec3 scaled(const glm::vec3& linear) const { return linear * scale_; }
  // The 8-bit value: scaled, clamped to [0, 1], encoded, rounded.
  std::uint8_t byte(float linear) const;
  float scale() const { return scale_; }
  Encoding encoding() const { return srgb_ ? Encoding::kSrgb : Encoding::kLinear; }
  // The light a display shows for the value byte() writes: an sRGB display
  // decodes every 8-bit value it is sent (a linear output's values too), so
  // FLIP judges what a viewer of the PNG sees.
  float displayed(float linear) const;
  // The linear value an 8-bit value stands for (byte()'s inverse, up to its
  // rounding and clamping).
  float decoded(std::uint8_t byte) const;

 private:
  float scale_;
  bool srgb_;
};

// An image's displayed light (Encoder::displayed), an 8-bit image's
// (displayedByte), and an 8-bit image's linear values (Encoder::decoded),
// pixel by pixel.
LinearImage displayedLight(const LinearImage& image, const Encoder& encoder);
LinearImage displayedLight(const FrameImage& image);
LinearImage decodeBytes(const FrameImage& image, const Encoder& encoder);
// A linear image's 8-bit values (Encoder::byte), as a PNG of it holds them.
FrameImage encodeBytes(const LinearImage& image, const Encoder& encoder);
// An 8-bit image as a float output holds it: the transfer function undone,
// the exposure kept (Encoder::scaled of the light each value stands for, up
// to its rounding), whatever the encoding.
LinearImage scaledLight(const FrameImage& image, const Encoder& encoder);

// The sRGB transfer function (IEC 61966-2-1) of a value in [0, 1].
float srgbEncode(float linear);

// Its inverse: the linear value an sRGB display shows for an encoded one.
float srgbDecode(float encoded);
// srgbDecode(byte / 255) of each 8-bit value.
float displayedByte(std::uint8_t byte);

// Linear [0, 1] -> 8 bits, rounded to nearest; values outside are clamped.
std::uint8_t toByte(float v);

}  // namespace glint
