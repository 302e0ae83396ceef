#pragma once

#include <optional>
#include <string>
#include <vector>

#include "client/commands/frame_overrides.h"
#include "client/raster/headless_gl.h"
#include "client/farm/tile_backend.h"
#include "common/geometry/bvh.h"
#include "common/render/tile.h"
#include "common/scene/scene.h"

namespace glint {

// Options of `glint render`; unset optionals keep the scene file's value.
struct RenderOptions {
  std::string scene;
  std::string output;
  FrameOverrides frame;             // the frame's and mask's options, as every command has them
  std::string maskOut;              // PNG of the mask, "" none
  int threads = 0;                  // 0: every hardware thread
  std::optional<TileRect> crop;     // --crop: only this window of the frame
  std::optional<BvhBuilder> bvh;    // in process only; unset: SAH
  RemoteOptions remote;             // --server ... (none renders in process), --stall-timeout, --tls-*
  std::string provenanceOut;        // PNG of who traced which tile, "" none
  std::string statsPath;            // "" none, "-" stdout
  int frames = 1;                   // frames rendered (the last is written); > 1 prints medians
  bool quiet = false;               // no progress and no summary on stderr
  bool progress = false;            // --progress: each frame's progress even off a terminal
  std::optional<gl::GlBackend> gl;  // --gl: the hybrid frame's headless OpenGL; unset: the default
};

// Loads the scene, applies the options, renders and writes the image (its
// format from the output's extension). Throws
// InputError for bad input (nothing is written then).
void runRender(const RenderOptions& options);

// The scene with the command-line overrides applied and checked.
void applyOverrides(const RenderOptions& options, Scene& scene);

}  // namespace glint
