#pragma once

#include <array>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/geometry/bounds.h"
#include "common/geometry/bvh.h"
#include "common/scene/scene.h"

namespace glint {

// Where an irradiance field's probes lie: a regular grid over the scene's
// bounds, at the centres of equal cells (so no probe lies on the bounds'
// walls), settings.probes along the longest side and the others in
// proportion. What filling a batch of probes needs, without their values.
class FieldGrid {
 public:
  FieldGrid(const Bounds3& bounds, const FieldSettings& settings);

  const FieldSettings& settings() const { return settings_; }
  const glm::ivec3& counts() const { return counts_; }
  int probeCount() const { return counts_.x * counts_.y * counts_.z; }
  glm::vec3 position(int probe) const;  // origin() + cell x step()
  const glm::vec3& origin() const { return origin_; }
  const glm::vec3& step() const { return step_; }
  // Where a ray's distance is clamped to in the visibility map.
  float maxDistance() const;

 private:
  FieldSettings settings_;
  glm::ivec3 counts_;
  glm::vec3 origin_;  // probe (0, 0, 0)
  glm::vec3 step_;    // between neighbouring probes
};

// The indirect light of a scene as a field the raster and the tracer read:
// probes on a FieldGrid, each holding
//  - the irradiance the light from other surfaces brings it, as spherical
//    harmonics to order 2 convolved with the cosine lobe (shIrradiance),
//  - and, in an equal-area octahedral map of kMapSide^2 texels, the mean
//    and mean square distance its rays travelled (clamped to maxDistance()),
//    the visibility DDGI keeps (Majercik et al., JCGT 2019).
// A point's irradiance blends its cell's eight probes by their trilinear
// weights, their side of the normal and whether they see the point
// (shading.glsl's probeShare and probeVisibility), so that light does not
// leak through a wall. Where too little of the weight sees the point, the
// field cannot decide, and the point is traced instead.
class IrradianceField {
 public:
  static constexpr int kMapSide = 8;
  static constexpr int kMapTexels = kMapSide * kMapSide;
  // A lookup the field decides: the probes that see the point carry at
  // least kDecidedShare of its weight before visibility, and those in doubt
  // (visibilityInDoubt) at most kDoubtShare (a probe across a thin wall
  // holds the other room's light, which even a small weight would leak).
  static constexpr float kDecidedShare = 0.1f;
  static constexpr float kDoubtShare = 0.01f;

  struct Probe {
    std::array<glm::vec3, 9> irradiance{};  // A_l L_k per basis function
    std::array<glm::vec2, kMapTexels> moments{};  // mean, mean square distance per texel
  };
  // A probe as floats, as it travels between client and server: its
  // irradiance's 27, then its moments' 128.
  static constexpr int kProbeFloats = 9 * 3 + kMapTexels * 2;
  static void writeProbe(const Probe& probe, std::span<float, kProbeFloats> out);
  static Probe readProbe(std::span<const float, kProbeFloats> in);
  struct Lookup {
    glm::vec3 irradiance{0.0f};
    bool decided = false;
    int sightRays = 0;     // the rays that confirmed probes (any-hit rays)
    int sightBlocked = 0;  // those that found a probe hidden
  };

  IrradianceField(const Bounds3& bounds, const FieldSettings& settings);

  const FieldGrid& grid() const { return grid_; }
  const FieldSettings& settings() const { return grid_.settings(); }
  const glm::ivec3& counts() const { return grid_.counts(); }
  int probeCount() const { return grid_.probeCount(); }
  glm::vec3 position(int probe) const { return grid_.position(probe); }
  const glm::vec3& origin() const { return grid_.origin(); }
  const glm::vec3& step() const { return grid_.step(); }
  float maxDistance() const { return grid_.maxDistance(); }
  Probe& probe(int i) { return probes_[static_cast<std::size_t>(i)]; }
  const Probe& probe(int i) const { return probes_[static_cast<std::size_t>(i)]; }

  // The irradiance at p toward unit normal n (p on a surface, n on the side
  // the light is wanted). With `sight` (the tracer's scene), a ray from the
  // looked-up point confirms each probe the map lets through: a probe
  // behind a wall of zero thickness or inside an object, which the coarse
  // map cannot tell from one that sees the point, carries no weight, and
  // no probe is left in doubt (OpenGL, without rays, traces such points).
  Lookup irradiance(const glm::vec3& p, const glm::vec3& n, const Bvh* sight = nullptr) const;

  // The visibility texel of a point of the map (octahedralPoint's).
  static int texel(const glm::vec2& point);

 private:
  int index(const glm::ivec3& cell) const {
    return (cell.z * counts().y + cell.y) * counts().x + cell.x;
  }

  FieldGrid grid_;
  std::vector<Probe> probes_;
};

}  // namespace glint
