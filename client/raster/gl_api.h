#pragma once

// Prototypes only for decltype below; nothing links against them.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <functional>

namespace glint::gl {

// The OpenGL entry points Glint uses, loaded through the context's own
// GetProcAddress (OSMesa or GLFW), so that one program can drive either
// without linking two GL libraries' symbols against each other.
#define GLINT_GL_FUNCTIONS(X) \
  X(GetError) \
  X(Viewport) \
  X(Scissor) \
  X(Clear) \
  X(ClearBufferfv) \
  X(ClearBufferuiv) \
  X(Enable) \
  X(Disable) \
  X(CullFace) \
  X(DepthFunc) \
  X(ClipControl) \
  X(PixelStorei) \
  X(ReadPixels) \
  X(DrawPixels) \
  X(WindowPos2i) \
  X(Finish) \
  X(CreateShader) \
  X(ShaderSource) \
  X(CompileShader) \
  X(GetShaderiv) \
  X(GetShaderInfoLog) \
  X(DeleteShader) \
  X(CreateProgram) \
  X(AttachShader) \
  X(LinkProgram) \
  X(GetProgramiv) \
  X(GetProgramInfoLog) \
  X(DeleteProgram) \
  X(UseProgram) \
  X(GetUniformLocation) \
  X(Uniform1i) \
  X(Uniform2i) \
  X(Uniform3i) \
  X(Uniform1iv) \
  X(Uniform1f) \
  X(Uniform2f) \
  X(Uniform1fv) \
  X(Uniform2fv) \
  X(Uniform3fv) \
  X(Uniform4fv) \
  X(UniformMatrix3x2fv) \
  X(UniformMatrix4fv) \
  X(GenVertexArrays) \
  X(BindVertexArray) \
  X(DeleteVertexArrays) \
  X(GenBuffers) \
  X(BindBuffer) \
  X(BufferData) \
  X(DeleteBuffers) \
  X(EnableVertexAttribArray) \
  X(VertexAttribPointer) \
  X(VertexAttribIPointer) \
  X(DrawArrays) \
  X(DrawElements) \
  X(GenTextures) \
  X(BindTexture) \
  X(TexImage2D) \
  X(TexImage3D) \
  X(TexParameteri) \
  X(ActiveTexture) \
  X(DeleteTextures) \
  X(GenFramebuffers) \
  X(BindFramebuffer) \
  X(DeleteFramebuffers) \
  X(CheckFramebufferStatus) \
  X(GenRenderbuffers) \
  X(BindRenderbuffer) \
  X(DeleteRenderbuffers) \
  X(RenderbufferStorage) \
  X(FramebufferRenderbuffer) \
  X(FramebufferTextureLayer) \
  X(DrawBuffer) \
  X(DrawBuffers) \
  X(ReadBuffer)

struct Api {
#define GLINT_GL_MEMBER(name) decltype(&::gl##name) name = nullptr;
  GLINT_GL_FUNCTIONS(GLINT_GL_MEMBER)
#undef GLINT_GL_MEMBER
};

// Loads every entry point; throws InputError naming the first one missing.
Api loadApi(const std::function<void*(const char*)>& getProcAddress);

}  // namespace glint::gl
