#pragma once

#include <cstddef>

#include "common/base/file_source.h"
#include "common/image/decode_budget.h"
#include "common/scene/frame_limits.h"

namespace glint {

// Upper bounds on what a scene may make the loader allocate; a file over one
// is rejected before the allocation, with a message naming the limit.
struct LoadLimits {
  std::size_t maxFileBytes = kDefaultMaxFileBytes;        // one scene, mesh or texture file
  std::size_t maxTriangles = 30'000'000;                  // all meshes together
  std::size_t maxVertices = 30'000'000;                   // all meshes together
  std::size_t maxTexturePixels = kDefaultMaxTexturePixels;  // one texture
  std::size_t maxImagePixels = FrameLimits::kMaxPixels;   // the rendered image
  int maxJsonDepth = 64;                                  // arrays and objects nested in a scene file
  // What one scene holds once built: texels, meshes, BVH (SceneBudget counts it).
  std::size_t maxSceneBytes = std::size_t{8} << 30;
};

}  // namespace glint
