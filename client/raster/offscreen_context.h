#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "client/raster/gl_api.h"
#include "client/raster/headless_gl.h"

namespace glint::gl {

// The backends this build has (those whose libraries it found), the
// default first: EGL (the one Mesa keeps, and as fast: docs/performance.md),
// then OSMesa.
const std::vector<GlBackend>& builtGlBackends();

// A headless OpenGL context (a compatibility profile, Mesa's software
// rasterizer where there is no GPU) from `backend`, by default the first of
// builtGlBackends() that can be had. The raster pass draws into a
// framebuffer object (client/raster/raster_target.h). Throws InputError naming the
// backend and why it cannot be had (each tried, by default).
class OffscreenContext {
 public:
  OffscreenContext(int width, int height, std::optional<GlBackend> backend = std::nullopt);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  const Api& api() const { return api_; }
  GlBackend backend() const { return backend_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  std::unique_ptr<HeadlessGl> context_;
  GlBackend backend_;
  int width_;
  int height_;
  Api api_;
};

}  // namespace glint::gl
