#include "common/scene/texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "common/scene/shading.h"

namespace glint {
namespace {

int wrappedIndex(int i, int n, TextureWrap mode) { return glsl::wrappedIndex(i, n, static_cast<int>(mode)); }

glm::vec3 texel(const Image& image, const std::array<TextureWrap, 2>& wrap, int x, int y) {
  return image.texel(static_cast<std::size_t>(wrappedIndex(y, image.height, wrap[1])) *
                         static_cast<std::size_t>(image.width) +
                     static_cast<std::size_t>(wrappedIndex(x, image.width, wrap[0])));
}

glm::vec3 lookup(const Image& image, ImageFilter filter, const std::array<TextureWrap, 2>& wrap, const glm::vec2& uv) {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return texel(image, wrap, 0, 0);
  const glm::ivec2 modes(static_cast<int>(wrap[0]), static_cast<int>(wrap[1]));
  const glm::vec2 p = glsl::imagePoint(uv, modes, glm::vec2(image.width, image.height));
  if (filter == ImageFilter::kNearest) return texel(image, wrap, static_cast<int>(p.x), static_cast<int>(p.y));
  const glm::ivec2 c = glsl::bilinearCorner(p);
  return glsl::bilinearBlend(texel(image, wrap, c.x, c.y), texel(image, wrap, c.x + 1, c.y),
                             texel(image, wrap, c.x, c.y + 1), texel(image, wrap, c.x + 1, c.y + 1), p);
}

}  // namespace

int checkerIndex(const glm::vec2& uv, float scale) {
  const double u = std::floor(double(uv.x) * scale);
  const double v = std::floor(double(uv.y) * scale);
  const double sum = u + v;
  if (!std::isfinite(sum)) return 0;
  // sum mod 2 without fmod's library call: below 2^53 the sum is an exact
  // integer, and from 2^53 on every double is even.
  const double magnitude = std::abs(sum);
  return magnitude < 0x1p53 && (static_cast<std::int64_t>(magnitude) & 1) != 0 ? 1 : 0;
}

glm::vec3 Texture::evaluate(const glm::vec2& given) const {
  const glm::vec2 uv = transform ? transform->apply(given) : given;
  switch (type) {
    case TextureType::kSolid:
      return colors[0];
    case TextureType::kChecker:
      return colors[checkerIndex(uv, scale)];
    case TextureType::kImage:
      return lookup(*image, filter, wrap, uv);
  }
  return colors[0];
}

}  // namespace glint
