#pragma once

#include <functional>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "client/gl_api.h"
#include "common/geometry/bounds.h"
#include "common/scene/scene.h"

namespace glint::gl {

// Shadow maps of a scene's point and spot lights for the raster pass: a cube of six
// square faces per light, all in one depth texture array (light k's faces are
// layers 6k .. 6k+5). Face f looks from the light along kFaces[f].m: a world
// point v (relative to the light) with m . v > 0 falls on texel
// floor(((s . v, t . v) / (m . v) + 1) / 2 * size) of that face, and a
// texel holds the distance from the light to the nearest surface along its
// centre's direction, divided by the light's far plane (GL's own depth is
// not used: the shaders write this distance, linear). The fragment shaders
// read the maps (kFragmentShading's shadowVisibility) and classify each
// point as lit, shadowed or undecided.
class ShadowMaps {
 public:
  explicit ShadowMaps(const Api& gl) : gl_(gl) {}
  ~ShadowMaps();
  ShadowMaps(const ShadowMaps&) = delete;
  ShadowMaps& operator=(const ShadowMaps&) = delete;

  // Draws every object's depth (distance from `eye` / `far`) with the given
  // view-projection into the bound framebuffer.
  using DepthPass = std::function<void(const glm::mat4& viewProjection, const glm::vec3& eye, float far)>;
  // Draws the maps, `size` texels a face edge, of the point and spot lights
  // `casts` flags (a spot's map is a point light's: its cone only darkens),
  // for geometry within `bounds`. The default framebuffer is bound afterwards.
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
  const Api& gl_;
  unsigned texture_ = 0;
  unsigned framebuffer_ = 0;
  int size_ = 0;
  std::vector<int> firstLayer_;  // per light, -1: no map
  std::vector<float> far_;       // per light
};

}  // namespace glint::gl
