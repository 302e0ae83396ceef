#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <string>

#include "client/raster/headless_gl.h"
#include "common/base/error.h"

namespace glint::gl {
namespace {

std::string eglError(const char* what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
  return std::string("OpenGL (egl): ") + what + " (EGL error " + code + ")";
}

// An OpenGL compatibility context on Mesa's surfaceless EGL platform: no
// window, no display server, no GPU needed (llvmpipe where there is none).
class EglContext : public HeadlessGl {
 public:
  EglContext() {
    const char* extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!extensions || std::string(extensions).find("EGL_MESA_platform_surfaceless") == std::string::npos) {
      throw InputError(
          "OpenGL (egl): this EGL has no surfaceless platform (EGL_MESA_platform_surfaceless); "
          "Mesa's libegl-mesa0 has it");
    }
    const auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    display_ = getPlatformDisplay ? getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr)
                                  : EGL_NO_DISPLAY;
    if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, nullptr, nullptr)) {
      throw InputError(eglError("cannot open the surfaceless display"));
    }
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 3,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 3,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
                                 EGL_NONE};
    if (!eglBindAPI(EGL_OPENGL_API) ||
        (context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes)) == EGL_NO_CONTEXT) {
      throw InputError(eglError("cannot create a context (OpenGL 3.3 compatibility)"));
    }
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      const std::string why = eglError("cannot make the context current");
      eglDestroyContext(display_, context_);
      throw InputError(why);
    }
  }
  // The display stays initialised: it is one for the whole process, and
  // eglTerminate would end it for every other context too.
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
  }
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  void* procAddress(const char* name) const override { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<HeadlessGl> makeEglContext() {
  return std::make_unique<EglContext>();
}

}  // namespace glint::gl
