#include "client/stats_json.h"

#include <iostream>

#include "common/error.h"

namespace glint {

nlohmann::json toJson(const FrameRecord& r) {
  nlohmann::json j = {
      {"frame", r.frame},
      {"width", r.width},
      {"height", r.height},
      {"masked_pixels", r.maskedPixels},
      {"tiles", r.tiles},
      {"rays",
       {{"primary", r.rays.primary},
        {"shadow", r.rays.shadow},
        {"shadow_blocked", r.rays.shadowBlocked},
        {"reflection", r.rays.reflection},
        {"refraction", r.rays.refraction},
        {"total", r.rays.total()}}},
      {"nonfinite_samples", r.rays.nonFiniteSamples},
      {"dropped_triangles", r.droppedTriangles},
      {"load_ms", r.loadMs},
      {r.remote ? "connect_ms" : "bvh_ms", r.prepareMs},
      {"trace_ms", r.traceMs},
      {"frame_ms", r.frameMs},
      {"total_ms", r.totalMs},
  };
  if (r.plan) j["effects"] = toJson(*r.plan);
  if (r.hybrid) {
    j["raster_ms"] = r.hybrid->rasterMs;
    j["readback_ms"] = r.hybrid->readbackMs;
    j["compose_ms"] = r.hybrid->composeMs;
  }
  if (r.remote && r.hybrid) j["network_ms"] = r.hybrid->networkMs;
  return j;
}

StatsWriter::StatsWriter(const std::string& path) : path_(path) {}

void StatsWriter::write(const FrameRecord& record) {
  if (path_ != "-" && !file_.is_open()) file_.open(path_, std::ios::trunc);  // at the first record: a render
                                                                            // that fails first leaves no file
  std::ostream& out = path_ == "-" ? std::cout : file_;
  out << toJson(record).dump() << '\n' << std::flush;
  if (!out) throw InputError("--stats " + path_ + ": cannot write the file");
}

}  // namespace glint
