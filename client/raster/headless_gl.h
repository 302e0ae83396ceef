#pragma once

#include <memory>

#include "common/base/enum_words.h"

namespace glint::gl {

// Where a headless OpenGL context comes from: OSMesa (Mesa's off-screen
// library, gone from Mesa 25.1 on) or EGL without a window (Mesa's
// surfaceless platform). Both run Mesa's llvmpipe here and draw the same
// bytes (tests/client/hybrid_test.cpp).
enum class GlBackend { kOsmesa, kEgl };

}  // namespace glint::gl

namespace glint {
template <>
struct EnumWords<gl::GlBackend> {
  static constexpr std::array<std::pair<gl::GlBackend, std::string_view>, 2> kWords{
      {{gl::GlBackend::kOsmesa, "osmesa"}, {gl::GlBackend::kEgl, "egl"}}};
};
}  // namespace glint

namespace glint::gl {

// A context of one backend, current on the thread that made it; its GL
// functions by name. The raster pass draws into its own framebuffer object
// (client/raster/raster_target.h), so the context needs no framebuffer of its own
// to speak of.
class HeadlessGl {
 public:
  virtual ~HeadlessGl() = default;
  virtual void* procAddress(const char* name) const = 0;
};

// A context of `backend` (width x height for OSMesa's own buffer); throws
// InputError saying why it cannot be had.
std::unique_ptr<HeadlessGl> makeOsmesaContext(int width, int height);
std::unique_ptr<HeadlessGl> makeEglContext();

}  // namespace glint::gl
