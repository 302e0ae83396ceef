#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "client/tile_backend.h"
#include "common/bvh.h"
#include "common/scene.h"
#include "common/tile.h"

namespace glint {

// Options of `glint render`; unset optionals keep the scene file's value.
struct RenderOptions {
  std::string scene;
  std::string output;
  std::optional<MaskRule> mask;
  std::optional<float> maskThreshold;  // overrides the scene's min_reflectivity
  std::string maskOut;                 // PNG of the mask, "" none
  std::optional<int> shadowMap;        // overrides the scene's mask.shadow_map
  int threads = 0;             // 0: every hardware thread
  int tileSize = 64;
  std::optional<int> samples;
  std::optional<SamplePattern> pattern;
  std::optional<float> adaptiveThreshold;
  std::optional<FilterType> filter;
  std::optional<int> maxDepth;
  std::optional<float> minWeight;
  std::optional<glm::vec3> eye;     // --eye, --look-at, --up: the camera's, overriding the scene's
  std::optional<glm::vec3> lookAt;
  std::optional<glm::vec3> up;
  std::optional<float> fovY;        // --fov, degrees
  std::optional<int> width;
  std::optional<int> height;
  std::optional<std::uint32_t> seed;
  std::optional<Encoding> encoding;  // --encoding, 8-bit outputs
  std::optional<float> exposure;     // --exposure EV
  std::optional<TileRect> crop;      // --crop: only this window of the frame
  std::optional<BvhBuilder> bvh;  // in process only; unset: SAH
  RemoteOptions remote;       // --server ... (none renders in process), --stall-timeout, --tls-*
  std::string provenanceOut;  // PNG of who traced which tile, "" none
  std::string statsPath;  // "" none, "-" stdout
  int frames = 1;          // frames rendered (the last is written); > 1 prints medians
  bool quiet = false;
};

// Loads the scene, applies the options, renders and writes the image (its
// format from the output's extension). Throws
// InputError for bad input (nothing is written then).
void runRender(const RenderOptions& options);

// The scene with the command-line overrides applied and checked.
void applyOverrides(const RenderOptions& options, Scene& scene);

}  // namespace glint
