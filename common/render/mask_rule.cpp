#include "common/render/mask_rule.h"

namespace glint {

bool materialMasked(const Material& m, const MaskSettings& mask) {
  switch (mask.rule) {
    case MaskRule::kAll:
      return true;
    case MaskRule::kNone:
      return false;
    case MaskRule::kAuto:
    case MaskRule::kPerceptual:
      break;
  }
  if (m.raytrace == RaytraceRule::kAlways) return true;
  if (m.raytrace == RaytraceRule::kNever) return false;
  return m.reflectivity > mask.minReflectivity || m.transparency > mask.minTransparency;
}

bool backgroundMasked(const Scene& scene, const MaskSettings& mask) {
  return scene.environment != nullptr && (mask.rule == MaskRule::kAuto || mask.rule == MaskRule::kPerceptual);
}

}  // namespace glint
