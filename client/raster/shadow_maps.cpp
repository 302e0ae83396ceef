#include "client/raster/shadow_maps.h"

#include <algorithm>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "client/raster/raster_shaders.h"
#include "common/math/basis.h"
#include "common/base/error.h"

namespace glint::gl {
namespace {

// A face's orthonormal basis: m the direction it looks along, s and t its
// texture axes (texel x grows with s, texel y with t).
struct Face {
  glm::vec3 s, t, m;
};
constexpr Face kFaces[6] = {
    {{0, 0, -1}, {0, -1, 0}, {1, 0, 0}},  {{0, 0, 1}, {0, -1, 0}, {-1, 0, 0}},
    {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},    {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}},
    {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}},   {{-1, 0, 0}, {0, -1, 0}, {0, 0, -1}},
};

// The face's view-projection: clip x = s . v, y = t . v, w = m . v (v from
// the light), a 90-degree square frustum. The near plane only clips (depth is
// written linear by the shaders), so it sits very close to the light.
glm::mat4 faceViewProjection(const Face& face, const glm::vec3& light, float far) {
  glm::mat4 view(1.0f);
  const glm::vec3 rows[3] = {face.s, face.t, -face.m};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) view[c][r] = rows[r][c];
    view[3][r] = -glm::dot(rows[r], light);
  }
  return glm::perspective(glm::radians(90.0f), 1.0f, far * 1e-6f, far) * view;
}

// A directional light's layer: clip x = s . (p - c) / R, y = t . (p - c) / R,
// z = m . (p - c) / R, w = 1 (the depth is written by the shaders; z only
// clips, and depth clamping is on).
glm::mat4 parallelViewProjection(const glm::vec3& s, const glm::vec3& t, const glm::vec3& m, const glm::vec3& c,
                                 float r) {
  glm::mat4 out(1.0f);
  const glm::vec3 rows[3] = {s, t, m};
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) out[col][row] = rows[row][col] / r;
    out[3][row] = -glm::dot(rows[row], c) / r;
  }
  return out;
}

// Just beyond the scene's farthest corner as seen from the light.
float farPlane(const Bounds3& bounds, const glm::vec3& light) {
  float far = 1.0f;
  for (const glm::vec3& p : bounds.corners()) far = std::max(far, glm::length(p - light) * 1.01f);
  return far;
}

}  // namespace

ShadowMaps::~ShadowMaps() { release(); }

void ShadowMaps::release() {
  if (framebuffer_) gl_.DeleteFramebuffers(1, &framebuffer_);
  if (texture_) gl_.DeleteTextures(1, &texture_);
  framebuffer_ = texture_ = 0;
  size_ = 0;
}

void ShadowMaps::build(const std::vector<Light>& lights, const std::vector<bool>& casts, const Bounds3& bounds,
                       int size, const DepthPass& drawDepth) {
  release();
  firstLayer_.assign(lights.size(), -1);
  far_.assign(lights.size(), 1.0f);
  axisS_.assign(lights.size(), glm::vec3(0.0f));
  axisT_.assign(lights.size(), glm::vec3(0.0f));
  centre_ = bounds.empty() ? glm::vec3(0.0f) : bounds.centre();
  radius_ = bounds.empty() ? 1.0f : std::max(glm::length(bounds.max - bounds.min) * 0.505f, 1e-6f);
  int layers = 0;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    if (!casts[i] || softLight(lights[i]) || bounds.empty()) continue;
    firstLayer_[i] = layers;
    if (lights[i].type == LightType::kDirectional) {
      orthonormalBasis(lights[i].direction, axisS_[i], axisT_[i]);
      far_[i] = 2.0f * radius_;
      layers += 1;
    } else {
      far_[i] = farPlane(bounds, lights[i].position);
      layers += 6;
    }
  }
  size_ = size;
  if (layers == 0) return;
  gl_.GenTextures(1, &texture_);
  gl_.BindTexture(GL_TEXTURE_2D_ARRAY, texture_);
  gl_.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT32F, size, size, layers, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                 nullptr);
  gl_.GenFramebuffers(1, &framebuffer_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.DrawBuffer(GL_NONE);
  gl_.ReadBuffer(GL_NONE);
  gl_.Viewport(0, 0, size, size);
  gl_.Enable(GL_DEPTH_TEST);
  gl_.DepthFunc(GL_LESS);
  gl_.Disable(GL_STENCIL_TEST);
  for (std::size_t i = 0; i < lights.size(); ++i) {
    if (firstLayer_[i] < 0) continue;
    if (lights[i].type == LightType::kDirectional) {
      bindLayer(firstLayer_[i]);
      const glm::vec3& m = lights[i].direction;
      drawDepth(parallelViewProjection(axisS_[i], axisT_[i], m, centre_, radius_), centre_ - radius_ * m, far_[i], m);
      continue;
    }
    for (int f = 0; f < 6; ++f) {
      bindLayer(firstLayer_[i] + f);
      drawDepth(faceViewProjection(kFaces[f], lights[i].position, far_[i]), lights[i].position, far_[i],
                glm::vec3(0.0f));
    }
  }
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void ShadowMaps::bindLayer(int layer) {
  gl_.FramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, texture_, 0, layer);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    const int size = size_;
    release();
    throw InputError("OpenGL: cannot draw into a " + std::to_string(size) + " x " + std::to_string(size) +
                     " shadow map; try a smaller --shadow-map");
  }
  gl_.Clear(GL_DEPTH_BUFFER_BIT);
}

void ShadowMaps::setUniforms(unsigned program, int unit, std::size_t lights, bool enabled) const {
  const auto at = [&](const char* name) { return gl_.GetUniformLocation(program, name); };
  const bool maps = enabled && texture_ && firstLayer_.size() == lights;
  const std::vector<int> layers = maps ? firstLayer_ : std::vector<int>(lights, -1);
  if (!layers.empty()) gl_.Uniform1iv(at("uShadowLayer"), static_cast<GLsizei>(layers.size()), layers.data());
  if (maps) {
    const auto n = static_cast<GLsizei>(far_.size());
    gl_.Uniform1fv(at("uShadowFar"), n, far_.data());
    gl_.Uniform3fv(at("uShadowAxisS"), n, glm::value_ptr(axisS_[0]));
    gl_.Uniform3fv(at("uShadowAxisT"), n, glm::value_ptr(axisT_[0]));
    gl_.Uniform3fv(at("uShadowCentre"), 1, glm::value_ptr(centre_));
    gl_.Uniform1f(at("uShadowRadius"), radius_);
  }
  gl_.Uniform1i(at("uShadowSize"), size_);
  glm::vec3 s[6], t[6], m[6];
  for (int f = 0; f < 6; ++f) {
    s[f] = kFaces[f].s;
    t[f] = kFaces[f].t;
    m[f] = kFaces[f].m;
  }
  gl_.Uniform3fv(at("uShadowFaceS"), 6, glm::value_ptr(s[0]));
  gl_.Uniform3fv(at("uShadowFaceT"), 6, glm::value_ptr(t[0]));
  gl_.Uniform3fv(at("uShadowFaceM"), 6, glm::value_ptr(m[0]));
  gl_.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_2D_ARRAY, texture_);
  gl_.Uniform1i(at("uShadowMaps"), unit);
  gl_.ActiveTexture(GL_TEXTURE0);
}

}  // namespace glint::gl
