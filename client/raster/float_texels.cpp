#include "client/raster/float_texels.h"

#include "common/base/error.h"

namespace glint::gl {

void uploadFloatTexels(const Api& gl, unsigned& name, std::vector<glm::vec4> texels, int records, int fields,
                       int perRow, const std::string& what, const std::string& remedy) {
  const int rows = (records + perRow - 1) / perRow;
  texels.resize(static_cast<std::size_t>(rows) * static_cast<std::size_t>(perRow * fields), glm::vec4(0.0f));
  if (!name) gl.GenTextures(1, &name);
  gl.BindTexture(GL_TEXTURE_2D, name);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, perRow * fields, rows, 0, GL_RGBA, GL_FLOAT, texels.data());
  if (gl.GetError() != GL_NO_ERROR) {
    throw InputError("OpenGL: cannot hold the " + std::to_string(records) + " " + what + " (" + remedy + ")");
  }
}

void uploadFloatTexels(const Api& gl, unsigned& name, const std::vector<glm::vec3>& texels, int records, int fields,
                       int perRow, const std::string& what, const std::string& remedy) {
  std::vector<glm::vec4> rgba;
  rgba.reserve(texels.size());
  for (const glm::vec3& t : texels) rgba.emplace_back(t, 1.0f);
  uploadFloatTexels(gl, name, std::move(rgba), records, fields, perRow, what, remedy);
}

}  // namespace glint::gl
