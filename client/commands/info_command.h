#pragma once

#include <optional>
#include <string>

#include "client/commands/frame_overrides.h"
#include "client/raster/headless_gl.h"

namespace glint {

// Options of `glint info`.
struct InfoOptions {
  std::string scene;
  FrameOverrides frame;             // the frame's and mask's options, as every command has them
  bool raster = true;               // --no-raster: skip the raster pass that counts the traced pixels
  int threads = 0;                  // that fill the irradiance field; 0: one per hardware thread
  std::optional<gl::GlBackend> gl;  // --gl: the raster pass's headless OpenGL; unset: the default
};

// Prints what a scene holds and what rendering it would do: the image and
// camera, the box around its objects (and the camera "fit" would give),
// its objects, triangles, materials, textures and lights, the effect plan,
// and the hybrid frame's share of traced pixels (from one raster pass,
// nothing traced). Throws InputError for bad input.
void runInfo(const InfoOptions& options);

}  // namespace glint
