#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>

#include "client/farm/distribution_report.h"
#include "client/farm/server_link.h"
#include "client/farm/server_list.h"
#include "client/farm/tile_dispatcher.h"

namespace glint {

// All the farm knows of one server, in the one record every part reads,
// kept by the ServerPool at the server's index (its links' and the
// dispatcher's key) for as long as the client runs.
struct FarmServer {
  ServerAddress address;
  std::shared_ptr<ServerLink> link;

  // Membership (the pool): a server that leaves keeps its record, and takes
  // it again if it comes back.
  bool member = true;   // false once it left the farm
  int joinedFrame = 0;  // the report (frame) that says it joined; 0: one of the first
  int leftFrame = -1;   // the report that says it left

  // Backoff (the pool).
  bool everReady = false;  // in this link's life
  int failures = 0;        // in a row
  std::chrono::steady_clock::time_point retryAt;
  // When it first answered Busy in this run of failures (none: it did not).
  std::optional<std::chrono::steady_clock::time_point> busySince;

  // Its pace, learnt from frame to frame: the dispatcher is told it when the
  // server joins a frame and gives back what the frame taught.
  ServerPace pace;

  // The frame's report (the tile service): its row in the report's servers
  // (-1: none), what it did, and what its link had counted at the start of
  // each render().
  ServerReport report;
  int reportRow = -1;
  std::uint64_t bytesInAtStart = 0;
  std::uint64_t bytesOutAtStart = 0;
};

}  // namespace glint
