#include "client/offscreen_context.h"

#include <GL/osmesa.h>

#include "common/base/error.h"

#if defined(__SANITIZE_ADDRESS__)
// Mesa's OSMesa keeps about 480 bytes per context after
// OSMesaDestroyContext (also after releasing the context first); under
// -DGLINT_SANITIZE=ON LeakSanitizer is told that this leak is not Glint's.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOSMesa.so\n"; }
#endif

namespace glint::gl {

struct OffscreenContext::Impl {
  OSMesaContext context = nullptr;
};

OffscreenContext::OffscreenContext(int width, int height)
    : impl_(std::make_unique<Impl>()),
      pixels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4),
      width_(width),
      height_(height) {
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
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
