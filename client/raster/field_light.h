#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "client/raster/gl_api.h"
#include "common/render/emitter_patches.h"
#include "common/render/irradiance_field.h"

namespace glint::gl {

// Texels a probe takes in the field's texture (FIELD_PROBE_TEXELS): its 9
// irradiance coefficients' 27 floats packed four a texel (FIELD_SH_TEXELS),
// then its visibility map's moments (in r and g).
constexpr int kFieldShTexels = (9 * 3 + 3) / 4;
constexpr int kFieldProbeTexels = kFieldShTexels + IrradianceField::kMapTexels;
constexpr int kFieldProbesPerRow = 64;  // FIELD_PROBES_PER_ROW

// The light of an irradiance field as the raster reads it, the tracer's
// Tracer::fieldLight: the field's probes, uploaded once in a float texture
// read exactly, and the emitting triangles (common/render/emitter_patches.h)
// in uniforms.
class FieldLight {
 public:
  FieldLight(const Api& gl, const IrradianceField& field, const EmitterPatches& emitters);
  ~FieldLight();
  FieldLight(const FieldLight&) = delete;
  FieldLight& operator=(const FieldLight&) = delete;

  // The field's uniforms of a program in use; its texture on this unit.
  void setUniforms(unsigned program, int fieldUnit) const;

 private:
  const Api& gl_;
  const IrradianceField& field_;
  unsigned probes_ = 0;
  std::vector<glm::vec3> emitters_;  // per triangle: its three corners, its emission
};

}  // namespace glint::gl
