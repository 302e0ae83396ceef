#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "proto/messages.h"
#include "proto/scene_bundle.h"

namespace glint::proto {

// A whole upload to a server that holds none of the bundle's files: every
// file's chunks, then the SceneUpload (what a raw peer in a test sends, and
// the fuzz seeds hold).
inline std::vector<std::vector<std::uint8_t>> encodeFullUpload(const SceneBundle& bundle,
                                                               std::size_t chunkBytes = kFileChunkBytes) {
  const BundleDigest d = digest(bundle);
  std::vector<std::vector<std::uint8_t>> frames;
  std::size_t i = 0;
  for (const auto& [path, bytes] : bundle.files) {
    for (auto& chunk : encodeFileChunks(bytes, d.files[i], chunkBytes)) frames.push_back(std::move(chunk));
    ++i;
  }
  frames.push_back(encodeSceneUpload(d.scene, bundle, d.files));
  return frames;
}

}  // namespace glint::proto
