#pragma once

#include "client/gl_api.h"

namespace glint::gl {

// A multisampled framebuffer (colour, depth) that a frame's raster is drawn
// into and resolved from (the samples averaged) into the default
// framebuffer's colour: the raster's anti-aliasing, so that GL's pixels are
// sampled like the tracer's at the seam between them. As many samples as
// asked, up to what the GL implementation offers (llvmpipe: 4).
class MultisampleTarget {
 public:
  explicit MultisampleTarget(const Api& gl) : gl_(gl) {}
  ~MultisampleTarget();
  MultisampleTarget(const MultisampleTarget&) = delete;
  MultisampleTarget& operator=(const MultisampleTarget&) = delete;

  // Makes a target of this size with min(samples, the most GL offers)
  // samples, anew when either changes; false when that is fewer than 2 (or
  // GL cannot make it). The default framebuffer stays bound.
  bool prepare(int width, int height, int samples);
  // Binds the target prepare() made.
  void bind();
  // Averages the samples into the default framebuffer's colour and binds
  // the default framebuffer again.
  void resolve();

 private:
  void release();

  const Api& gl_;
  unsigned framebuffer_ = 0;
  unsigned buffers_[2] = {};  // colour, depth
  int width_ = 0;
  int height_ = 0;
  int samples_ = 0;
};

}  // namespace glint::gl
