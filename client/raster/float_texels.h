#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "client/raster/gl_api.h"

namespace glint::gl {

// Records of `fields` RGBA float texels each, `perRow` records a row (the
// last row padded), into texture `name` (made on first use, bound to the
// active unit) for the shaders to read exactly with texelFetch. Throws
// InputError naming `records` `what` and `remedy` when OpenGL cannot hold
// them.
void uploadFloatTexels(const Api& gl, unsigned& name, std::vector<glm::vec4> texels, int records, int fields,
                       int perRow, const std::string& what, const std::string& remedy);
// The same of RGB texels, held as RGBA (alpha 1), which llvmpipe fetches
// faster than three floats.
void uploadFloatTexels(const Api& gl, unsigned& name, const std::vector<glm::vec3>& texels, int records, int fields,
                       int perRow, const std::string& what, const std::string& remedy);

}  // namespace glint::gl
