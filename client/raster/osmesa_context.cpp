#include <GL/osmesa.h>

#include <vector>

#include "client/raster/headless_gl.h"
#include "common/base/error.h"

namespace glint::gl {
namespace {

// An OSMesa compatibility context drawing into memory of its own (RGBA8).
class OsmesaContext : public HeadlessGl {
 public:
  OsmesaContext(int width, int height)
      : pixels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4) {
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              0,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_COMPAT_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    context_ = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context_) throw InputError("OpenGL (osmesa): cannot create a context (OpenGL 3.3 compatibility)");
    if (!OSMesaMakeCurrent(context_, pixels_.data(), GL_UNSIGNED_BYTE, width, height)) {
      OSMesaDestroyContext(context_);
      throw InputError("OpenGL (osmesa): cannot make the context current");
    }
  }
  ~OsmesaContext() override { OSMesaDestroyContext(context_); }
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  void* procAddress(const char* name) const override { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); }

 private:
  std::vector<unsigned char> pixels_;  // the context's colour buffer
  OSMesaContext context_ = nullptr;
};

}  // namespace

std::unique_ptr<HeadlessGl> makeOsmesaContext(int width, int height) {
  return std::make_unique<OsmesaContext>(width, height);
}

}  // namespace glint::gl
