#include "client/commands/stats_json.h"

#include <iostream>

#include "common/base/error.h"

namespace glint {
namespace {

nlohmann::json toJson(const RayStats& rays) {
  return {{"primary", rays.primary},       {"shadow", rays.shadow},
          {"shadow_blocked", rays.shadowBlocked}, {"reflection", rays.reflection},
          {"refraction", rays.refraction}, {"total", rays.total()}};
}

nlohmann::json toJson(const ServerReport& s) {
  nlohmann::json j = {{"address", s.address},
                      {"state", enumWord(s.state)},
                      {"tiles", s.tiles},
                      {"masked_pixels", s.maskedPixels},
                      {"rays", toJson(s.rays)},
                      {"busy_ms", s.busyMs},
                      {"rtt_ms", s.rttMs},
                      {"bytes_in", s.bytesIn},
                      {"bytes_out", s.bytesOut},
                      {"joined", s.joined}};
  if (!s.why.empty()) j["why"] = s.why;
  return j;
}

}  // namespace

nlohmann::json toJson(const FrameRecord& r) {
  nlohmann::json j = {
      {"frame", r.frame},
      {"width", r.width},
      {"height", r.height},
      {"masked_pixels", r.maskedPixels},
      {"tiles", r.tiles},
      {"rays", toJson(r.rays)},
      {"nonfinite_samples", r.rays.nonFiniteSamples},
      {"dropped_triangles", r.droppedTriangles},
      {"load_ms", r.loadMs},
      {r.remote ? "connect_ms" : "bvh_ms", r.prepareMs},
      {"trace_ms", r.traceMs},
      {"frame_ms", r.frameMs},
      {"total_ms", r.totalMs},
  };
  if (r.crop) j["crop"] = {r.crop->x, r.crop->y, r.crop->x + r.crop->width, r.crop->y + r.crop->height};
  // What the frame traced of what a full trace would: its pixels, and its
  // camera rays against the full trace's pixels x samples.
  const double pixels = r.crop ? static_cast<double>(r.crop->pixelCount()) : double(r.width) * double(r.height);
  j["traced_share"] = pixels > 0 ? static_cast<double>(r.maskedPixels) / pixels : 0.0;
  j["primary_share"] = pixels > 0 ? static_cast<double>(r.rays.primary) / (pixels * r.samples) : 0.0;
  if (r.plan) j["effects"] = toJson(*r.plan);
  if (r.field) {
    j["field"] = {{"probes", r.field->probes},
                  {"rays_a_probe", r.field->raysAProbe},
                  {"ms", r.field->ms},
                  {"rays", toJson(r.field->rays)}};
  }
  if (r.rays.paths > 0) {
    j["paths"] = {{"count", r.rays.paths},
                  {"bounces_mean", static_cast<double>(r.rays.pathBounces) / static_cast<double>(r.rays.paths)},
                  {"bounces_max", r.rays.longestPath},
                  {"light_samples", r.rays.lightSamples}};
  }
  if (r.hybrid) {
    j["raster_ms"] = r.hybrid->rasterMs;
    j["shadow_map_ms"] = r.hybrid->shadowMapMs;
    j["shadow_edge_pixels"] = r.shadowEdgePixels;
    j["out_of_focus_pixels"] = r.outOfFocusPixels;
    j["raster_edge_pixels"] = r.rasterEdgePixels;
    j["readback_ms"] = r.hybrid->readbackMs;
    j["compose_ms"] = r.hybrid->composeMs;
  }
  if (r.remote && r.hybrid) j["network_ms"] = r.hybrid->networkMs;
  if (r.distribution) {
    nlohmann::json servers = nlohmann::json::array();
    for (const ServerReport& s : r.distribution->servers) servers.push_back(toJson(s));
    j["servers"] = std::move(servers);
    j["reissued_tiles"] = r.distribution->reissuedTiles;
    j["duplicated_tiles"] = r.distribution->duplicatedTiles;
    j["hedged_tiles"] = r.distribution->hedgedTiles;
  }
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
