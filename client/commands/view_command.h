#pragma once

#include <optional>
#include <string>
#include <vector>

#include "client/commands/frame_overrides.h"
#include "client/farm/tile_backend.h"
#include "common/geometry/bvh.h"
#include "common/scene/scene.h"

namespace glint {

// Options of `glint view`.
struct ViewOptions {
  std::string scene;
  RemoteOptions remote;        // --server ... (none traces in process), --stall-timeout, --tls-*
  FrameOverrides frame;  // the frame's and mask's options, as every command has them (the size: the window's)
  int threads = 0;
  std::optional<BvhBuilder> bvh;  // in process only; unset: SAH
  int frames = 0;              // > 0: close after this many frames (scripts, tests)
  std::string screenshot;      // PNG of the last frame, "" none
};

// Opens a window on the scene: left drag orbits around the camera's target,
// right drag pans, the wheel zooms; M cycles the mask rule (auto,
// perceptual, all, none), O shows the mask over the image, Q or Escape closes. While the
// camera moves each frame is a one-sample preview; when it rests, the frame
// with the scene's samples follows (equal to glint render's): whole, or,
// when every pixel is traced in process, summed in passes of 1, 2, 4, ...
// samples a pixel, each shown (common/render/progressive_frame.h). The window may
// be resized; the frame follows its size. The title shows the frame time and
// its steps. Throws InputError for bad input.
void runView(const ViewOptions& options);

}  // namespace glint
