#include "client/raster/field_light.h"

#include <algorithm>
#include <array>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "client/raster/float_texels.h"

namespace glint::gl {
namespace {

constexpr const char* kRemedy = "a coarser field, or --mask all traces every pixel";

}  // namespace

FieldLight::FieldLight(const Api& gl, const IrradianceField& field, const EmitterPatches& emitters)
    : gl_(gl), field_(field) {
  for (const EmitterPatches::Patch& p : emitters.patches()) {
    emitters_.insert(emitters_.end(), {p.corner, p.corner + p.edge1, p.corner + p.edge2, p.radiance});
  }
  std::vector<glm::vec4> texels;
  texels.reserve(static_cast<std::size_t>(field.probeCount() * kFieldProbeTexels));
  for (int i = 0; i < field.probeCount(); ++i) {
    const IrradianceField::Probe& p = field.probe(i);
    std::array<float, 4 * kFieldShTexels> packed{};
    for (std::size_t k = 0; k < p.irradiance.size(); ++k) std::copy_n(&p.irradiance[k].x, 3, &packed[3 * k]);
    for (int t = 0; t < kFieldShTexels; ++t) texels.push_back(glm::make_vec4(&packed[static_cast<std::size_t>(4 * t)]));
    for (const glm::vec2& m : p.moments) texels.emplace_back(m, 0.0f, 0.0f);
  }
  if (texels.empty()) return;
  uploadFloatTexels(gl_, probes_, std::move(texels), field.probeCount(), kFieldProbeTexels, kFieldProbesPerRow,
                    "probes of the irradiance field", kRemedy);
}

FieldLight::~FieldLight() {
  if (probes_) gl_.DeleteTextures(1, &probes_);
}

void FieldLight::setUniforms(unsigned program, int fieldUnit) const {
  const auto at = [&](const char* name) { return gl_.GetUniformLocation(program, name); };
  gl_.Uniform3fv(at("uFieldOrigin"), 1, glm::value_ptr(field_.origin()));
  gl_.Uniform3fv(at("uFieldStep"), 1, glm::value_ptr(field_.step()));
  const glm::ivec3& counts = field_.counts();
  gl_.Uniform3i(at("uFieldCounts"), counts.x, counts.y, counts.z);
  const auto triangles = static_cast<int>(emitters_.size() / 4);
  gl_.Uniform1i(at("uEmitterCount"), triangles);
  if (triangles > 0) {
    gl_.Uniform3fv(at("uEmitters"), static_cast<GLsizei>(emitters_.size()), glm::value_ptr(emitters_.front()));
  }
  gl_.Uniform1i(at("uField"), fieldUnit);
  gl_.ActiveTexture(GL_TEXTURE0 + fieldUnit);
  gl_.BindTexture(GL_TEXTURE_2D, probes_);
  gl_.ActiveTexture(GL_TEXTURE0);
}

}  // namespace glint::gl
