#include "client/stats_json.h"

namespace glint {

nlohmann::json frameStats(int frame, int width, int height, std::size_t maskedPixels,
                          const RayStats& rays, const FrameTimes& times, const EffectPlan& plan,
                          std::size_t droppedTriangles) {
  return {
      {"frame", frame},
      {"width", width},
      {"height", height},
      {"masked_pixels", maskedPixels},
      {"rays",
       {{"primary", rays.primary},
        {"shadow", rays.shadow},
        {"shadow_blocked", rays.shadowBlocked},
        {"reflection", rays.reflection},
        {"refraction", rays.refraction},
        {"total", rays.total()}}},
      {"nonfinite_samples", rays.nonFiniteSamples},
      {"dropped_triangles", droppedTriangles},
      {"load_ms", times.loadMs},
      {"bvh_ms", times.bvhMs},
      {"trace_ms", times.traceMs},
      {"total_ms", times.totalMs},
      {"effects", toJson(plan)},
  };
}

}  // namespace glint
