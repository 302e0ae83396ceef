#include "client/raster/gl_api.h"

#include <string>

#include "common/base/error.h"

namespace glint::gl {

Api loadApi(const std::function<void*(const char*)>& getProcAddress) {
  Api api;
#define GLINT_GL_LOAD(name)                                                    \
  api.name = reinterpret_cast<decltype(api.name)>(getProcAddress("gl" #name)); \
  if (!api.name)                                                               \
    throw InputError("OpenGL: the driver has no gl" #name                      \
                     " (OpenGL 4.5, or 3.3 with ARB_clip_control, is needed)");
  GLINT_GL_FUNCTIONS(GLINT_GL_LOAD)
#undef GLINT_GL_LOAD
  return api;
}

}  // namespace glint::gl
