#include "client/multisample_target.h"

#include <algorithm>

namespace glint::gl {

MultisampleTarget::~MultisampleTarget() { release(); }

void MultisampleTarget::release() {
  if (framebuffer_) gl_.DeleteFramebuffers(1, &framebuffer_);
  if (buffers_[0]) gl_.DeleteRenderbuffers(2, buffers_);
  framebuffer_ = buffers_[0] = buffers_[1] = 0;
}

bool MultisampleTarget::prepare(int width, int height, int samples) {
  GLint offered = 0;
  gl_.GetIntegerv(GL_MAX_SAMPLES, &offered);
  samples = std::min(samples, static_cast<int>(offered));
  if (samples < 2) return false;
  if (framebuffer_ && width == width_ && height == height_ && samples == samples_) return true;
  release();
  gl_.GenFramebuffers(1, &framebuffer_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.GenRenderbuffers(2, buffers_);
  const GLenum formats[2] = {GL_RGBA8, GL_DEPTH24_STENCIL8};
  const GLenum attachments[2] = {GL_COLOR_ATTACHMENT0, GL_DEPTH_STENCIL_ATTACHMENT};
  for (int i = 0; i < 2; ++i) {
    gl_.BindRenderbuffer(GL_RENDERBUFFER, buffers_[i]);
    gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, formats[i], width, height);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, attachments[i], GL_RENDERBUFFER, buffers_[i]);
  }
  const bool complete = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) {
    release();
    return false;
  }
  width_ = width;
  height_ = height;
  samples_ = samples;
  return true;
}

void MultisampleTarget::bind() { gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_); }

void MultisampleTarget::resolve() {
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  gl_.BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace glint::gl
