#pragma once

#include <cstddef>
#include <fstream>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "client/farm/distribution_report.h"
#include "client/raster/hybrid_frame.h"
#include "common/render/effects.h"
#include "common/render/ray_stats.h"

namespace glint {

// Everything one --stats record says about a frame. This file owns the
// record's schema; docs/stats.md lists its keys.
struct FrameRecord {
  int frame = 0;
  int width = 0;
  int height = 0;
  int samples = 1;               // the frame's samples a pixel
  std::optional<TileRect> crop;  // --crop: the window rendered
  std::size_t maskedPixels = 0;
  std::size_t outOfFocusPixels = 0;  // of maskedPixels, traced because the lens blurs them
  std::size_t shadowEdgePixels = 0;  // of maskedPixels, traced where the shadow maps could not decide
  std::size_t rasterEdgePixels = 0;  // of maskedPixels, traced because they straddle an edge of the raster
  int tiles = 0;
  RayStats rays;
  const EffectPlan* plan = nullptr;
  std::size_t droppedTriangles = 0;
  bool remote = false;     // tiles traced by a glintd
  double loadMs = 0.0;     // reading and checking the scene and its files
  double prepareMs = 0.0;  // in process: the BVH build; remote: connect, upload and the server's build
  // The irradiance field the frame reads, filled once before the first
  // frame (its time apart from prepareMs, its rays apart from the frame's).
  struct Field {
    int probes = 0;
    int raysAProbe = 0;
    double ms = 0.0;
    RayStats rays;
  };
  std::optional<Field> field;
  double traceMs = 0.0;    // the tile service filling the traced pixels
  double frameMs = 0.0;    // the frame alone
  double totalMs = 0.0;    // frame 0: since the start, load and preparation included; then the frame
  std::optional<HybridTimes> hybrid;  // the hybrid frame's other steps
  const DistributionReport* distribution = nullptr;  // through glintd: who did what
};

nlohmann::json toJson(const FrameRecord& record);

// Writes one record a line to stdout ("-") or to a file, created (or
// truncated) at the first record.
class StatsWriter {
 public:
  explicit StatsWriter(const std::string& path);
  void write(const FrameRecord& record);

 private:
  std::string path_;
  std::ofstream file_;
};

}  // namespace glint
