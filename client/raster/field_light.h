#pragma once

#include "client/raster/gl_api.h"
#include "common/render/emitter_patches.h"
#include "common/render/irradiance_field.h"

namespace glint::gl {

// Texels a probe takes in the field's texture (FIELD_PROBE_TEXELS): its 9
// irradiance coefficients, then its visibility map's moments (in r and g).
constexpr int kFieldProbeTexels = 9 + IrradianceField::kMapTexels;
constexpr int kFieldProbesPerRow = 64;  // FIELD_PROBES_PER_ROW
// An emitter point's texels (position, power, normal), and points a row.
constexpr int kEmitterPointFields = 3;
constexpr int kEmitterPointsPerRow = 256;

// The light of an irradiance field as the raster reads it, the tracer's
// Tracer::fieldLight: the field's probes (uploaded once) and the emitters'
// fixed points (common/render/emitter_patches.h; uploaded each frame, whose
// light samples say how many) in two float textures read exactly.
class FieldLight {
 public:
  FieldLight(const Api& gl, const IrradianceField& field);
  ~FieldLight();
  FieldLight(const FieldLight&) = delete;
  FieldLight& operator=(const FieldLight&) = delete;

  // The emitters' points of the frame.
  void prepare(const EmitterPatches& patches);
  // The field's uniforms of a program in use; its textures on these units.
  void setUniforms(unsigned program, int fieldUnit, int emitterUnit) const;

 private:
  const Api& gl_;
  const IrradianceField& field_;
  unsigned probes_ = 0;
  unsigned emitters_ = 0;
  int emitterCount_ = 0;
};

}  // namespace glint::gl
