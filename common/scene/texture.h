#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include <glm/mat2x2.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/base/enum_words.h"
#include "common/image/texel_image.h"

namespace glint {

enum class TextureType { kSolid, kChecker, kImage };
enum class ImageFilter { kNearest, kBilinear };
// Where an image texture's coordinate outside [0, 1] reads, along u or v,
// as OpenGL's (and glTF's sampler) wrap modes: the image repeated, repeated
// mirrored every other time, or its edge texels stretched.
enum class TextureWrap { kRepeat, kMirroredRepeat, kClampToEdge };

template <>
struct EnumWords<TextureType> {
  static constexpr std::array<std::pair<TextureType, std::string_view>, 3> kWords{
      {{TextureType::kSolid, "solid"}, {TextureType::kChecker, "checker"}, {TextureType::kImage, "image"}}};
};
template <>
struct EnumWords<ImageFilter> {
  static constexpr std::array<std::pair<ImageFilter, std::string_view>, 2> kWords{
      {{ImageFilter::kNearest, "nearest"}, {ImageFilter::kBilinear, "bilinear"}}};
};
template <>
struct EnumWords<TextureWrap> {
  static constexpr std::array<std::pair<TextureWrap, std::string_view>, 3> kWords{
      {{TextureWrap::kRepeat, "repeat"},
       {TextureWrap::kMirroredRepeat, "mirrored_repeat"},
       {TextureWrap::kClampToEdge, "clamp_to_edge"}}};
};

// An affine map of texture coordinates applied before a lookup (glTF's
// KHR_texture_transform): uv' = m uv + offset.
struct UvTransform {
  glm::mat2 m{1.0f};
  glm::vec2 offset{0.0f};

  glm::vec2 apply(const glm::vec2& uv) const { return m * uv + offset; }
};

// The thesis's abstract texture: a colour at (u, v).
struct Texture {
  TextureType type = TextureType::kSolid;
  glm::vec3 colors[2] = {glm::vec3(1.0f), glm::vec3(0.0f)};  // solid uses colors[0]
  float scale = 1.0f;                                        // checker squares per unit of u and v
  std::shared_ptr<const Image> image;
  ImageFilter filter = ImageFilter::kNearest;
  std::array<TextureWrap, 2> wrap{TextureWrap::kRepeat, TextureWrap::kRepeat};  // along u, along v
  std::optional<UvTransform> transform;  // none: uv as given

  glm::vec3 evaluate(const glm::vec2& uv) const;
};

// Checker square index at (u, v): (floor(u s) + floor(v s)) mod 2, as the
// scene format defines it; 0 for coordinates that are not finite.
int checkerIndex(const glm::vec2& uv, float scale);

}  // namespace glint
