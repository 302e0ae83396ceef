#include "client/raster/raster_target.h"

#include <string>

#include "client/raster/image_rows.h"
#include "common/base/error.h"

namespace glint::gl {

RasterTarget::~RasterTarget() { release(); }

void RasterTarget::release() {
  if (framebuffer_) gl_.DeleteFramebuffers(1, &framebuffer_);
  if (buffers_[0]) gl_.DeleteRenderbuffers(3, buffers_);
  framebuffer_ = buffers_[0] = buffers_[1] = buffers_[2] = 0;
  width_ = height_ = 0;
}

void RasterTarget::bind(int width, int height) {
  if (framebuffer_ && width == width_ && height == height_) {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    return;
  }
  release();
  gl_.GenFramebuffers(1, &framebuffer_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.GenRenderbuffers(3, buffers_);
  const GLenum formats[3] = {GL_RGBA8, GL_R32UI, GL_DEPTH_COMPONENT32F};
  const GLenum attachments[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_DEPTH_ATTACHMENT};
  for (int i = 0; i < 3; ++i) {
    gl_.BindRenderbuffer(GL_RENDERBUFFER, buffers_[i]);
    gl_.RenderbufferStorage(GL_RENDERBUFFER, formats[i], width, height);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, attachments[i], GL_RENDERBUFFER, buffers_[i]);
  }
  const GLenum drawn[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  gl_.DrawBuffers(2, drawn);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    release();
    throw InputError("OpenGL: cannot make a " + std::to_string(width) + " x " + std::to_string(height) +
                     " framebuffer for the raster pass");
  }
  width_ = width;
  height_ = height;
}

void RasterTarget::clear(const std::uint8_t background[3], std::uint32_t backgroundSurface) {
  const GLfloat colour[4] = {background[0] / 255.0f, background[1] / 255.0f, background[2] / 255.0f, 1.0f};
  const GLuint surface[4] = {backgroundSurface, 0, 0, 0};
  const GLfloat far = 0.0f;
  gl_.ClearBufferfv(GL_COLOR, 0, colour);
  gl_.ClearBufferuiv(GL_COLOR, 1, surface);
  gl_.ClearBufferfv(GL_DEPTH, 0, &far);
}

void RasterTarget::readColour(const TileRect& window, std::vector<std::uint8_t>& rgb) const {
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
  readPixels(gl_, window, height_, GL_RGB, GL_UNSIGNED_BYTE, 3, rgb);
}

void RasterTarget::readSurface(std::vector<std::uint32_t>& surface) const {
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT1);
  readPixels(gl_, TileRect{0, 0, width_, height_}, height_, GL_RED_INTEGER, GL_UNSIGNED_INT, 1, surface);
}

void RasterTarget::readDepth(std::vector<float>& depth) const {
  readPixels(gl_, TileRect{0, 0, width_, height_}, height_, GL_DEPTH_COMPONENT, GL_FLOAT, 1, depth);
}

}  // namespace glint::gl
