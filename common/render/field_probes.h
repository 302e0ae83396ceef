#pragma once

#include <functional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/render/effects.h"
#include "common/render/irradiance_field.h"
#include "common/render/path_tracer.h"
#include "common/render/prepared_scene.h"
#include "common/render/sampling.h"
#include "common/render/ray_stats.h"
#include "common/scene/scene.h"

namespace glint {

// The unit direction of a point of [0, 1]^2 in the equal-area octahedral
// map (Clarberg 2008), octahedralPoint's inverse: uniform points of the
// square are uniform directions.
glm::vec3 octahedralDirection(const glm::vec2& point);

// Path transport's estimate of the light arriving at a field's probes (path_tracer.h, with one
// bounce fewer than the frame's, since the probe's rays stand for a surface's first bounce). A
// probe's rays leave in the directions of the scrambled Sobol points of its own key (the frame's
// seed and the probe's index), a power of two of them, so each visibility texel gets the same
// number; each ray adds the light the surface it meets reflects toward the probe (not what that
// surface emits: a point the field lights samples the emitters itself, Tracer) to the harmonics,
// and its distance to its texel's moments. A probe depends on nothing but its index: the same
// bytes for any threads, batches and servers. Thread-safe.
class ProbeTracer {
 public:
  ProbeTracer(const PreparedScene& prepared, const FrameSettings& frame, const FieldGrid& grid);
  IrradianceField::Probe trace(int index, RayStats& stats) const;

 private:
  const FieldGrid& grid_;
  FrameSettings probes_;  // the frame's, a bounce fewer
  EffectPlan plan_;
  PathTracer path_;
  SampleLayout layout_;
};

// Told, never concurrently, that `done` of `total` probes are filled, as
// they are.
using ProbeProgress = std::function<void(int done, int total)>;

// Fills probes [first, end) of the field (ProbeTracer), in parallel on the
// compute pool.
void fillProbes(IrradianceField& field, const PreparedScene& prepared, const FrameSettings& frame, int first, int end,
                RayStats& stats, const ProbeProgress& progress = {});

// A field over the scene's bounds, every probe filled.
IrradianceField buildField(const PreparedScene& prepared, const FrameSettings& frame, const FieldSettings& settings,
                           RayStats& stats, const ProbeProgress& progress = {});

}  // namespace glint
