#pragma once

#include <functional>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "client/raster/gl_api.h"
#include "common/geometry/bounds.h"
#include "common/scene/scene.h"

namespace glint::gl {

// Shadow maps of a scene's point, spot and directional lights for the raster
// pass, all in one depth texture array.
//  - A point or spot light gets a cube of six square faces (a spot's map is
//    a point light's: its cone only darkens). Face f looks from the light
//    along kFaces[f].m: a world point v (relative to the light) with
//    m . v > 0 falls on texel floor(((s . v, t . v) / (m . v) + 1) / 2 *
//    size) of that face, and a texel holds the distance from the light to the
//    nearest surface along its centre's direction.
//  - A directional light gets one orthographic layer over the sphere around
//    the scene's bounds (centre c, radius R), looking along its direction m
//    from the plane through c - R m: a point p falls on texel floor(((s .
//    (p - c), t . (p - c)) / R + 1) / 2 * size) (s, t: the layer's axes), and
//    a texel holds the distance from that plane to the nearest surface along
//    m.
// Depths are divided by the light's far plane (GL's own depth is not used:
// the shaders write this distance, linear). The fragment shaders read the
// maps (kFragmentShading's shadowVisibility) and classify each point as lit,
// shadowed or undecided.
class ShadowMaps {
 public:
  explicit ShadowMaps(const Api& gl) : gl_(gl) {}
  ~ShadowMaps();
  ShadowMaps(const ShadowMaps&) = delete;
  ShadowMaps& operator=(const ShadowMaps&) = delete;

  // Draws every object's depth with the given view-projection into the bound
  // framebuffer: its distance from `eye` / `far`, or with a non-zero unit
  // `axis` its distance along the axis from the plane through `eye`.
  using DepthPass = std::function<void(const glm::mat4& viewProjection, const glm::vec3& eye, float far,
                                       const glm::vec3& axis)>;
  // Draws the maps, `size` texels a face edge, of the point, spot and
  // directional lights `casts` flags, for geometry within `bounds`. The
  // default framebuffer is bound afterwards.
  void build(const std::vector<Light>& lights, const std::vector<bool>& casts, const Bounds3& bounds, int size,
             const DepthPass& drawDepth);
  int size() const { return size_; }  // 0: not built
  // Binds the maps to texture unit `unit` and sets the shaders' shadow
  // uniforms for a scene of `lights` lights; a light without a map (every
  // light when the maps are not built or not `enabled`) is lit wherever it
  // faces the surface.
  void setUniforms(unsigned program, int unit, std::size_t lights, bool enabled) const;

 private:
  void release();
  // Attaches `layer` to the framebuffer and clears it.
  void bindLayer(int layer);
  const Api& gl_;
  unsigned texture_ = 0;
  unsigned framebuffer_ = 0;
  int size_ = 0;
  std::vector<int> firstLayer_;  // per light, -1: no map
  std::vector<float> far_;       // per light
  std::vector<glm::vec3> axisS_, axisT_;  // per directional light: its layer's axes (unit)
  glm::vec3 centre_{0.0f};                // the sphere the directional layers span: c and R
  float radius_ = 1.0f;
};

}  // namespace glint::gl
