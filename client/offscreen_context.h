#pragma once

#include <memory>
#include <vector>

#include "client/gl_api.h"

namespace glint::gl {

// A headless OpenGL context (OSMesa, software rasterizer): a compatibility
// profile drawing into memory. Its own framebuffer has colour alone: the
// raster pass draws into a framebuffer object (client/raster_target.h).
class OffscreenContext {
 public:
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  const Api& api() const { return api_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<unsigned char> pixels_;  // the context's colour buffer (RGBA8)
  int width_;
  int height_;
  Api api_;
};

}  // namespace glint::gl
