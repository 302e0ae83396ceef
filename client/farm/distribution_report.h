#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/base/enum_words.h"
#include "common/render/ray_stats.h"
#include "common/render/tile.h"

namespace glint {

// How a server fared in a frame.
enum class ServerState {
  kOk,           // served the frame (or was ready to)
  kLost,         // was serving, and closed, failed or stalled
  kUnreachable,  // never became ready: no connection, refused, another build
  kLeft,         // no longer listed (--server-file, a name's addresses): told Goodbye
};

template <>
struct EnumWords<ServerState> {
  static constexpr std::array<std::pair<ServerState, std::string_view>, 4> kWords{{{ServerState::kOk, "ok"},
                                                                                   {ServerState::kLost, "lost"},
                                                                                   {ServerState::kUnreachable, "unreachable"},
                                                                                   {ServerState::kLeft, "left"}}};
};

// One server's part in a frame (the --stats "servers" objects, docs/stats.md):
// every member of the farm, and one that left for this frame.
struct ServerReport {
  std::string address;
  ServerState state = ServerState::kOk;
  std::string why;  // what went wrong, when it did
  bool joined = false;  // listed since the frame before (it serves once it holds the scene)
  std::size_t tiles = 0;         // results the frame took from it
  std::size_t maskedPixels = 0;  // in those tiles
  std::size_t probes = 0;        // of an irradiance field, in those that were its batches
  RayStats rays;
  double busyMs = 0.0;  // its threads' tracing time for those tiles
  double rttMs = 0.0;   // smallest round trip seen beyond tracing time
  std::uint64_t bytesIn = 0;   // received from it during the frame
  std::uint64_t bytesOut = 0;  // sent to it during the frame
};

// Who did what in the last frame: per server, and per tile (for the
// provenance image, client/provenance).
struct DistributionReport {
  std::vector<ServerReport> servers;
  std::size_t reissuedTiles = 0;    // taken again from a lost server
  std::size_t duplicatedTiles = 0;  // copies sent to a second server: the last bucket to an idle one, or hedged
  std::size_t hedgedTiles = 0;      // of those, copies of a tile outstanding past the frame's p95 latency
  std::vector<TileRect> rects;      // the frame's tiles
  std::vector<std::vector<std::uint8_t>> masks;  // per tile: its traced pixels (common/render/tile.h bits; empty: all)
  std::vector<int> deliveredBy;     // per tile: the index in `servers`, -1 when nothing was traced
  std::vector<bool> reissued;       // per tile
};

}  // namespace glint
