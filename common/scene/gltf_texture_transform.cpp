#include "common/scene/gltf_texture_transform.h"

#include <cmath>

namespace glint {

// In glTF's space p' = L p + t with L = R S and t = offset, where R turns
// the uvs counter-clockwise: u' = c u + s v, v' = -s u + c v (the
// extension's example: offset (0, 1), rotation 90 degrees and scale 0.5
// read the image's lower left quarter, turned clockwise). Glint's uv is
// F(p) = (u, 1 - v) = D p + e with D = diag(1, -1), e = (0, 1), so Glint's
// map is q' = D L D q + D (L e + t) + e.
UvTransform glintUvTransform(const KhrTextureTransform& t) {
  const double c = std::cos(t.rotation), s = std::sin(t.rotation);
  const double l00 = c * t.scale.x, l01 = s * t.scale.y, l10 = -s * t.scale.x, l11 = c * t.scale.y;  // rows
  UvTransform out;
  // D L D negates L's off-diagonal; glm takes columns.
  out.m =
      glm::mat2(static_cast<float>(l00), static_cast<float>(-l10), static_cast<float>(-l01), static_cast<float>(l11));
  out.offset = glm::vec2(static_cast<float>(l01 + t.offset.x), static_cast<float>(1.0 - (l11 + t.offset.y)));
  return out;
}

}  // namespace glint
