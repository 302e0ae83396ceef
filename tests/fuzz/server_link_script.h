#pragma once

#include <cstdint>
#include <vector>

#include "common/render/tile.h"
#include "common/render/tile_service.h"
#include "proto/scene_bundle.h"

namespace glint::fuzz {

// What the client asks of the fuzzed server (fuzz_server_link), and what its
// seeds answer (make_seeds): a scene of one file, then frame 1 and its two
// tiles, one of them masked.
inline const proto::SceneBundle& linkBundle() {
  static const proto::SceneBundle bundle{"{}", {{"mesh.obj", "v 0 0 0\n"}}};
  return bundle;
}

constexpr std::uint32_t kLinkFrame = 1;

inline std::vector<TileJob> linkJobs() {
  const TileRect masked{8, 0, 8, 8};
  return {{{0, 0, 8, 8}, {}}, {masked, std::vector<std::uint8_t>(maskByteCount(masked), 0x5a)}};
}

}  // namespace glint::fuzz
