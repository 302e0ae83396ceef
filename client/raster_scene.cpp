#include "client/raster_scene.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "client/raster_shaders.h"
#include "common/encoding.h"
#include "common/error.h"
#include "common/mask_rule.h"
#include "common/timing.h"

namespace glint::gl {
namespace {

// The texture units the fragment shaders read.
enum TextureUnit : int { kAtlasUnit = 0, kShadowMapUnit = 1, kStencilMarkUnit = 2 };

unsigned compile(const Api& gl, GLenum type, std::initializer_list<const char*> parts) {
  const unsigned shader = gl.CreateShader(type);
  const std::vector<const char*> sources(parts);
  gl.ShaderSource(shader, static_cast<GLsizei>(sources.size()), sources.data(), nullptr);
  gl.CompileShader(shader);
  GLint ok = 0;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetShaderInfoLog(shader, sizeof log, nullptr, log);
    gl.DeleteShader(shader);
    throw InputError(std::string("OpenGL: shader does not compile: ") + log);
  }
  return shader;
}

// variant: "" (colour and marks), or the #define of a variant that writes
// less (raster_shaders.h).
unsigned link(const Api& gl, const char* vertex, const char* fragment, const char* variant, bool stencilExport) {
  const unsigned vs = compile(gl, GL_VERTEX_SHADER, {vertex});
  const std::string prelude = fragmentPrelude(stencilExport);
  const unsigned fs = compile(gl, GL_FRAGMENT_SHADER, {prelude.c_str(), variant, kFragmentShading, fragment});
  const unsigned program = gl.CreateProgram();
  gl.AttachShader(program, vs);
  gl.AttachShader(program, fs);
  gl.LinkProgram(program);
  gl.DeleteShader(vs);
  gl.DeleteShader(fs);
  GLint ok = 0;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetProgramInfoLog(program, sizeof log, nullptr, log);
    throw InputError(std::string("OpenGL: shaders do not link: ") + log);
  }
  return program;
}

// Interleaved mesh vertex: position, shading normal, uv, face normal, material.
struct MeshVertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
  glm::vec3 faceNormal;
  std::int32_t material;
};

// Sphere impostor vertex: a corner of the bounding box and the sphere.
struct SphereVertex {
  glm::vec3 position;
  glm::vec4 sphere;
  std::int32_t material;
};

void attribute(const Api& gl, unsigned index, int size, std::size_t stride, std::size_t offset) {
  gl.EnableVertexAttribArray(index);
  gl.VertexAttribPointer(index, size, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(stride),
                         reinterpret_cast<const void*>(offset));
}

void intAttribute(const Api& gl, unsigned index, std::size_t stride, std::size_t offset) {
  gl.EnableVertexAttribArray(index);
  gl.VertexAttribIPointer(index, 1, GL_INT, static_cast<GLsizei>(stride), reinterpret_cast<const void*>(offset));
}

bool hasExtension(const Api& gl, const char* name) {
  GLint count = 0;
  gl.GetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const auto* extension = reinterpret_cast<const char*>(gl.GetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    if (extension && std::string(extension) == name) return true;
  }
  return false;
}

}  // namespace

RasterScene::RasterScene(const Api& api, const Scene& scene)
    : gl_(api),
      scene_(scene),
      plan_(EffectPlan::derive(scene)),
      stencilExport_(hasExtension(api, "GL_ARB_shader_stencil_export")),
      multisample_(api),
      shadowMaps_(api) {
  if (scene.lights.size() > kMaxLights) {
    throw InputError("the OpenGL path draws at most " + std::to_string(kMaxLights) + " lights; the scene has " +
                     std::to_string(scene.lights.size()));
  }
  if (scene.materials.size() > kMaxMaterials || scene.textures.size() > kMaxTextures) {
    throw InputError("the OpenGL path takes at most " + std::to_string(kMaxMaterials) + " materials and " +
                     std::to_string(kMaxTextures) + " textures");
  }
  for (std::uint32_t i = 0; i < scene.geometry.primitiveCount(); ++i) bounds_.expand(scene.geometry.primitiveBounds(i));
  const char* const variants[kShadings] = {"", "#define MARKS_ONLY\n", "#define TRACED\n"};
  for (int shading = 0; shading < kShadings; ++shading) {
    programs_[0][shading] = link(gl_, kMeshVertexShader, kMeshFragmentShader, variants[shading], stencilExport_);
    programs_[1][shading] = link(gl_, kSphereVertexShader, kSphereFragmentShader, variants[shading], stencilExport_);
  }
  uploadTextures();
  uploadMeshes();
  uploadSpheres();
}

RasterScene::~RasterScene() {
  for (Batch& b : batches_) {
    gl_.DeleteBuffers(1, &b.vbo);
    gl_.DeleteVertexArrays(1, &b.vao);
  }
  if (atlas_) gl_.DeleteTextures(1, &atlas_);
  if (stencilMarks_) gl_.DeleteTextures(1, &stencilMarks_);
  for (const auto& row : programs_) {
    for (unsigned program : row) gl_.DeleteProgram(program);
  }
}

void RasterScene::uploadTextures() {
  // Every image texture, one above the other, in one float RGB texture that
  // texelFetch reads exactly (no GL filtering: the shader filters as the tracer).
  int width = 1, height = 0;
  for (const Texture& t : scene_.textures) {
    textureRows_.push_back(static_cast<float>(height));
    if (t.type == TextureType::kImage) {
      width = std::max(width, t.image->width);
      height += t.image->height;
    }
  }
  std::vector<glm::vec3> texels(static_cast<std::size_t>(width) * static_cast<std::size_t>(std::max(height, 1)));
  int row = 0;
  for (const Texture& t : scene_.textures) {
    if (t.type != TextureType::kImage) continue;
    for (std::size_t y = 0; y < static_cast<std::size_t>(t.image->height); ++y) {
      const std::size_t w = static_cast<std::size_t>(t.image->width);
      for (std::size_t x = 0; x < w; ++x) {
        texels[(static_cast<std::size_t>(row) + y) * static_cast<std::size_t>(width) + x] = t.image->texel(y * w + x);
      }
    }
    row += t.image->height;
  }
  gl_.GenTextures(1, &atlas_);
  gl_.BindTexture(GL_TEXTURE_2D, atlas_);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, width, std::max(height, 1), 0, GL_RGB, GL_FLOAT, texels.data());
}

// A vertex array and buffer holding `count` vertices; left bound, so the
// caller describes the attributes next.
void RasterScene::newBatch(std::uint32_t material, bool spheres, const void* vertices, std::size_t count,
                           std::size_t vertexBytes) {
  Batch b;
  b.material = material;
  b.spheres = spheres;
  b.vertices = static_cast<int>(count);
  gl_.GenVertexArrays(1, &b.vao);
  gl_.BindVertexArray(b.vao);
  gl_.GenBuffers(1, &b.vbo);
  gl_.BindBuffer(GL_ARRAY_BUFFER, b.vbo);
  gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(count * vertexBytes), vertices, GL_STATIC_DRAW);
  batches_.push_back(b);
}

void RasterScene::uploadMeshes() {
  const Geometry& g = scene_.geometry;
  std::map<std::uint32_t, std::vector<MeshVertex>> byMaterial;
  for (std::size_t i = 0; i < g.triangles().size(); ++i) {
    const Triangle& t = g.triangles()[i];
    const std::uint32_t material = g.models()[t.model].material;
    const glm::vec3& face = g.faceNormals()[i];
    auto& vertices = byMaterial[material];
    for (std::uint32_t v : t.v) {
      vertices.push_back({g.positions()[v], g.normals()[v], g.uvs()[v], face, static_cast<std::int32_t>(material)});
    }
  }
  for (auto& [material, vertices] : byMaterial) {
    newBatch(material, false, vertices.data(), vertices.size(), sizeof(MeshVertex));
    attribute(gl_, 0, 3, sizeof(MeshVertex), offsetof(MeshVertex, position));
    attribute(gl_, 1, 3, sizeof(MeshVertex), offsetof(MeshVertex, normal));
    attribute(gl_, 2, 2, sizeof(MeshVertex), offsetof(MeshVertex, uv));
    attribute(gl_, 3, 3, sizeof(MeshVertex), offsetof(MeshVertex, faceNormal));
    intAttribute(gl_, 4, sizeof(MeshVertex), offsetof(MeshVertex, material));
  }
}

void RasterScene::uploadSpheres() {
  // The 12 triangles of a unit cube, corners in [-1, 1].
  static const int kCube[36] = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                                2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
  std::map<std::uint32_t, std::vector<SphereVertex>> byMaterial;
  for (const Sphere& s : scene_.geometry.spheres()) {
    auto& vertices = byMaterial[s.material];
    // A box slightly larger than the sphere, so rasterization covers its edge.
    const float half = s.radius * 1.01f;
    for (int corner : kCube) {
      const glm::vec3 c(corner & 1 ? 1.0f : -1.0f, corner & 2 ? 1.0f : -1.0f, corner & 4 ? 1.0f : -1.0f);
      vertices.push_back({s.centre + half * c, glm::vec4(s.centre, s.radius), static_cast<std::int32_t>(s.material)});
    }
  }
  for (auto& [material, vertices] : byMaterial) {
    newBatch(material, true, vertices.data(), vertices.size(), sizeof(SphereVertex));
    attribute(gl_, 0, 3, sizeof(SphereVertex), offsetof(SphereVertex, position));
    attribute(gl_, 1, 4, sizeof(SphereVertex), offsetof(SphereVertex, sphere));
    intAttribute(gl_, 2, sizeof(SphereVertex), offsetof(SphereVertex, material));
  }
}

RasterScene::Projection RasterScene::projection(const FrameSettings& frame) const {
  // The far plane just beyond the scene's farthest corner as seen from the eye.
  float far = 1.0f;
  if (!bounds_.empty()) {
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p(corner & 1 ? bounds_.max.x : bounds_.min.x, corner & 2 ? bounds_.max.y : bounds_.min.y,
                        corner & 4 ? bounds_.max.z : bounds_.min.z);
      far = std::max(far, glm::length(p - frame.camera.eye) * 1.01f);
    }
  }
  const glm::mat4 view = glm::lookAt(frame.camera.eye, frame.camera.lookAt, frame.camera.up);
  // The near plane only clips (what is nearer to the eye than far / 1000);
  // depth itself is written linear by the shaders.
  const glm::mat4 perspective = glm::perspective(glm::radians(frame.camera.fovY),
                                                 static_cast<float>(frame.width) / static_cast<float>(frame.height),
                                                 far * 1e-3f, far);
  return {perspective * view, far};
}

void RasterScene::setViewUniforms(unsigned program, const glm::mat4& viewProjection, const glm::vec3& eye, float far) {
  gl_.UseProgram(program);
  gl_.UniformMatrix4fv(gl_.GetUniformLocation(program, "uViewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
  gl_.Uniform1f(gl_.GetUniformLocation(program, "uFar"), far);
  gl_.Uniform3fv(gl_.GetUniformLocation(program, "uEye"), 1, glm::value_ptr(eye));
}

void RasterScene::setUniforms(unsigned program, const FrameSettings& frame, const Projection& projection,
                              bool antialiased) {
  setViewUniforms(program, projection.viewProjection, frame.camera.eye, projection.far);
  const auto at = [&](const char* name) { return gl_.GetUniformLocation(program, name); };
  gl_.Uniform1f(at("uExposureScale"), Encoder(frame.output).scale());
  gl_.Uniform1i(at("uSrgb"), frame.output.encoding == Encoding::kSrgb ? 1 : 0);
  std::vector<glm::vec3> positions, colors, attenuations;
  for (const PointLight& l : scene_.lights) {
    positions.push_back(l.position);
    colors.push_back(l.color);
    attenuations.push_back(l.attenuation);
  }
  gl_.Uniform1i(at("uLightCount"), static_cast<int>(scene_.lights.size()));
  if (!positions.empty()) {
    const auto n = static_cast<GLsizei>(positions.size());
    gl_.Uniform3fv(at("uLightPosition"), n, glm::value_ptr(positions[0]));
    gl_.Uniform3fv(at("uLightColor"), n, glm::value_ptr(colors[0]));
    gl_.Uniform3fv(at("uLightAttenuation"), n, glm::value_ptr(attenuations[0]));
  }
  std::vector<glm::vec4> materialColor, materialTerms;
  for (const Material& m : scene_.materials) {
    materialColor.emplace_back(m.color, static_cast<float>(m.texture));
    materialTerms.emplace_back(m.ambient, m.diffuse, m.specular, m.shininess);
  }
  if (!materialColor.empty()) {
    const auto n = static_cast<GLsizei>(materialColor.size());
    gl_.Uniform4fv(at("uMaterialColor"), n, glm::value_ptr(materialColor[0]));
    gl_.Uniform4fv(at("uMaterialTerms"), n, glm::value_ptr(materialTerms[0]));
  }
  std::vector<glm::vec4> info, size;
  std::vector<glm::vec3> color0, color1;
  for (std::size_t i = 0; i < scene_.textures.size(); ++i) {
    const Texture& t = scene_.textures[i];
    const bool image = t.type == TextureType::kImage;
    info.emplace_back(image ? 2.0f : 1.0f, t.scale, t.filter == ImageFilter::kBilinear ? 1.0f : 0.0f, textureRows_[i]);
    size.emplace_back(image ? static_cast<float>(t.image->width) : 1.0f, image ? static_cast<float>(t.image->height) : 1.0f,
                      0.0f, 0.0f);
    color0.push_back(t.colors[0]);
    color1.push_back(t.colors[1]);
  }
  if (!info.empty()) {
    const auto n = static_cast<GLsizei>(info.size());
    gl_.Uniform4fv(at("uTextureInfo"), n, glm::value_ptr(info[0]));
    gl_.Uniform4fv(at("uTextureSize"), n, glm::value_ptr(size[0]));
    gl_.Uniform3fv(at("uTextureColor0"), n, glm::value_ptr(color0[0]));
    gl_.Uniform3fv(at("uTextureColor1"), n, glm::value_ptr(color1[0]));
  }
  gl_.ActiveTexture(GL_TEXTURE0 + kAtlasUnit);
  gl_.BindTexture(GL_TEXTURE_2D, atlas_);
  gl_.Uniform1i(at("uAtlas"), kAtlasUnit);
  shadowMaps_.setUniforms(program, kShadowMapUnit, scene_.lights.size(), shadows_);
  gl_.Uniform1i(at("uShadowRadius"), antialiased ? 0 : kShadowRadius);
  gl_.Uniform1i(at("uUndecidedStencil"), undecidedStencil_);
  gl_.Uniform1i(at("uSkipMarked"), antialiased ? 1 : 0);
  gl_.Uniform1i(at("uStencilMarks"), kStencilMarkUnit);
}

std::string RasterScene::shadowEdgeNote(const MaskSettings& mask) const {
  if (stencilExport_ || mask.rule != MaskRule::kAuto || !rasterShadows(scene_, plan_, mask)) return "";
  return "note: this OpenGL has no ARB_shader_stencil_export: the edges of shadows on surfaces OpenGL draws are "
         "the shadow map's estimate, not traced";
}

bool RasterScene::prepareShadows(const MaskSettings& mask) {
  if (!rasterShadows(scene_, plan_, mask)) return false;
  if (shadowMaps_.size() != mask.shadowMap) {
    shadowMaps_.build(scene_.lights, plan_.lights, bounds_, mask.shadowMap,
                      [this](const glm::mat4& vp, const glm::vec3& eye, float far) { drawDepth(vp, eye, far); });
  }
  return true;
}

void RasterScene::drawDepth(const glm::mat4& viewProjection, const glm::vec3& eye, float far) {
  for (int spheres = 0; spheres < 2; ++spheres) {
    setViewUniforms(programs_[spheres][kTraced], viewProjection, eye, far);
    for (const Batch& b : batches_) {
      if (b.spheres != (spheres == 1)) continue;
      gl_.BindVertexArray(b.vao);
      gl_.DrawArrays(GL_TRIANGLES, 0, b.vertices);
    }
  }
  gl_.BindVertexArray(0);
  gl_.UseProgram(0);
}

void RasterScene::beginPass(const FrameSettings& frame, GLbitfield clear) {
  gl_.Viewport(0, 0, frame.width, frame.height);
  gl_.ClearColor(scene_.background.r, scene_.background.g, scene_.background.b, 1.0f);
  gl_.ClearStencil(0);
  gl_.StencilMask(0xff);
  gl_.Clear(clear);
  gl_.Enable(GL_DEPTH_TEST);
  gl_.DepthFunc(GL_LESS);
}

bool RasterScene::prepareAntialiased(const FrameSettings& frame) {
  return frame.sampling.samples >= 2 && multisample_.prepare(frame.width, frame.height, frame.sampling.samples);
}

double RasterScene::draw(const FrameSettings& frame, const MaskSettings& mask, bool colour) {
  const Clock::time_point start = Clock::now();
  shadows_ = prepareShadows(mask);
  const double shadowMs = msSince(start);
  undecidedStencil_ = mask.rule == MaskRule::kAuto ? kShadowEdgePixel : kRasterPixel;
  beginPass(frame, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  gl_.Enable(GL_STENCIL_TEST);
  gl_.StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);  // the visible object's flag wins
  drawBatches(frame, mask, colour ? Pass::kColourAndMarks : Pass::kMarks);
  return shadowMs;
}

void RasterScene::drawAntialiased(const FrameSettings& frame, std::span<const std::uint8_t> marks) {
  uploadMarks(frame, marks);
  multisample_.bind();
  beginPass(frame, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl_.Disable(GL_STENCIL_TEST);
  drawBatches(frame, MaskSettings{}, Pass::kAntialiased);
  multisample_.resolve();
}

// draw()'s marks as an integer texture the anti-aliased pass's fragments
// read (one byte a pixel, rows from the top: the shader flips).
void RasterScene::uploadMarks(const FrameSettings& frame, std::span<const std::uint8_t> marks) {
  if (marks.size() != static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height)) {
    throw std::invalid_argument("drawAntialiased: one stencil mark a pixel of the frame");
  }
  gl_.ActiveTexture(GL_TEXTURE0 + kStencilMarkUnit);
  if (!stencilMarks_) {
    gl_.GenTextures(1, &stencilMarks_);
    gl_.BindTexture(GL_TEXTURE_2D, stencilMarks_);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  gl_.BindTexture(GL_TEXTURE_2D, stencilMarks_);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_R8UI, frame.width, frame.height, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                 marks.data());
  gl_.ActiveTexture(GL_TEXTURE0);
}

void RasterScene::drawBatches(const FrameSettings& frame, const MaskSettings& mask, Pass pass) {
  const Projection vp = projection(frame);
  const bool antialiased = pass == Pass::kAntialiased;
  for (int spheres = 0; spheres < 2; ++spheres) {
    // A sphere's silhouette is decided in its fragment shader (discard): in
    // the anti-aliased pass it runs for every sample, where a mesh's edges
    // are the samples' coverage alone (4x the shading would cost the room
    // 48 ms of raster instead of 19).
    const bool perSample = antialiased && spheres == 1 && gl_.MinSampleShading;
    if (perSample) {
      gl_.Enable(GL_SAMPLE_SHADING);
      gl_.MinSampleShading(1.0f);
    }
    for (int shading = 0; shading < kShadings; ++shading) {
      bool uniformsSet = false;
      for (const Batch& b : batches_) {
        const bool masked = !antialiased && materialMasked(scene_.materials[b.material], mask);
        const Shading wanted = masked ? kTraced : pass == Pass::kMarks ? kMarksOnly : kColour;
        if (b.spheres != (spheres == 1) || wanted != shading) continue;
        if (!uniformsSet) {
          setUniforms(programs_[spheres][shading], frame, vp, antialiased);
          uniformsSet = true;
        }
        gl_.StencilFunc(GL_ALWAYS, masked ? kMaskedPixel : kRasterPixel, 0xff);
        gl_.BindVertexArray(b.vao);
        gl_.DrawArrays(GL_TRIANGLES, 0, b.vertices);
      }
    }
    if (perSample) gl_.Disable(GL_SAMPLE_SHADING);
  }
  gl_.BindVertexArray(0);
  gl_.UseProgram(0);
}

}  // namespace glint::gl
