#include "client/raster/offscreen_context.h"

#include <string>

#include "common/base/error.h"

#if defined(__SANITIZE_ADDRESS__)
// Mesa keeps a few hundred bytes per context after it is destroyed (OSMesa),
// and EGL's display for the process; under -DGLINT_SANITIZE=ON
// LeakSanitizer is told that these are not Glint's.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\nleak:libEGL_mesa.so\n";
}
#endif

namespace glint::gl {
namespace {

std::unique_ptr<HeadlessGl> make(GlBackend backend, int width, int height) {
  switch (backend) {
#if defined(GLINT_HAVE_EGL)
    case GlBackend::kEgl:
      return makeEglContext();
#endif
#if defined(GLINT_HAVE_OSMESA)
    case GlBackend::kOsmesa:
      return makeOsmesaContext(width, height);
#endif
    default:
      throw InputError("OpenGL (" + std::string(enumWord(backend)) + "): this glint was built without it");
  }
}

}  // namespace

const std::vector<GlBackend>& builtGlBackends() {
  static const std::vector<GlBackend> backends = {
#if defined(GLINT_HAVE_EGL)
    GlBackend::kEgl,
#endif
#if defined(GLINT_HAVE_OSMESA)
    GlBackend::kOsmesa,
#endif
  };
  return backends;
}

OffscreenContext::OffscreenContext(int width, int height, std::optional<GlBackend> backend)
    : backend_(backend.value_or(GlBackend::kEgl)), width_(width), height_(height) {
  if (backend) {
    context_ = make(*backend, width, height);
  } else {
    std::string why;
    for (const GlBackend b : builtGlBackends()) {
      try {
        context_ = make(b, width, height);
        backend_ = b;
        break;
      } catch (const InputError& e) {
        why += std::string(why.empty() ? "" : "; ") + e.what();
      }
    }
    if (!context_) throw InputError("no headless OpenGL context could be made: " + why);
  }
  api_ = loadApi([this](const char* name) { return context_->procAddress(name); });
}

OffscreenContext::~OffscreenContext() = default;

}  // namespace glint::gl
