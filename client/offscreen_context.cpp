#include "client/offscreen_context.h"

#include <GL/osmesa.h>

#include "common/error.h"

namespace glint::gl {

struct OffscreenContext::Impl {
  OSMesaContext context = nullptr;
};

OffscreenContext::OffscreenContext(int width, int height)
    : impl_(std::make_unique<Impl>()),
      pixels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4),
      width_(width),
      height_(height) {
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
                            OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                            OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  impl_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!impl_->context) throw InputError("OpenGL: cannot create an OSMesa context (OpenGL 3.3 compatibility)");
  if (!OSMesaMakeCurrent(impl_->context, pixels_.data(), GL_UNSIGNED_BYTE, width, height)) {
    OSMesaDestroyContext(impl_->context);
    throw InputError("OpenGL: cannot make the OSMesa context current");
  }
  api_ = loadApi([](const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); });
}

OffscreenContext::~OffscreenContext() {
  if (impl_->context) OSMesaDestroyContext(impl_->context);
}

}  // namespace glint::gl
