#include "client/raster/raster_scene.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "client/raster/float_texels.h"
#include "client/raster/pixel_mark.h"
#include "client/raster/shadow_rects.h"
#include "common/render/area_light.h"
#include "common/image/encoding.h"
#include "common/base/error.h"
#include "common/render/mask_rule.h"
#include "common/base/timing.h"

namespace glint::gl {
namespace {

// The texture units the fragment shaders read.
enum TextureUnit : int {
  kImageUnit = 0,
  kShadowMapUnit = 1,
  kEmissionUnit = 2,
  kAreaPointsUnit = 3,
  kFieldUnit = 4
};

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

unsigned link(const Api& gl, const ShaderVariant& variant) {
  const unsigned vs = compile(gl, GL_VERTEX_SHADER, {variant.sphere ? kSphereVertexShader : kMeshVertexShader});
  const std::string prelude = fragmentPrelude(variant);
  const unsigned fs = compile(gl, GL_FRAGMENT_SHADER,
                              {prelude.c_str(), kFragmentShading,
                               variant.sphere ? kSphereFragmentShader : kMeshFragmentShader});
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
    gl.DeleteProgram(program);
    throw InputError(std::string("OpenGL: shaders do not link: ") + log);
  }
  return program;
}

// Interleaved mesh vertex: position, shading normal, uv, face normal, object.
struct MeshVertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
  glm::vec3 faceNormal;
  std::int32_t object;
};

// Sphere impostor vertex: a corner of the bounding box, the sphere, its object.
struct SphereVertex {
  glm::vec3 position;
  glm::vec4 sphere;
  std::int32_t object;
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

}  // namespace

RasterScene::RasterScene(const Api& api, const Scene& scene)
    : gl_(api),
      scene_(scene),
      plan_(EffectPlan::derive(scene)),
      target_(api),
      shadowMaps_(api),
      penumbra_(scene, plan_) {
  std::vector<bool> casts(scene.lights.size(), false);  // the lights with shadow maps
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    if (softLight(scene.lights[i])) continue;
    punctualLights_.push_back(scene.lights[i]);
    punctualCasts_.push_back(plan_.lights[i]);
    spotLights_ = spotLights_ || scene.lights[i].type == LightType::kSpot;
    directionalLights_ = directionalLights_ || scene.lights[i].type == LightType::kDirectional;
    casts[i] = plan_.lights[i];
  }
  if (punctualLights_.size() > kMaxLights) {
    throw InputError("the OpenGL path draws at most " + std::to_string(kMaxLights) +
                     " point, spot and directional lights; the scene has " + std::to_string(punctualLights_.size()) +
                     " (--mask all traces them all)");
  }
  for (std::uint32_t i = 0; i < scene.geometry.primitiveCount(); ++i) bounds_.expand(scene.geometry.primitiveBounds(i));
  uploadTextures();
  uploadMeshes();
  uploadSpheres();
  if (plan_.shadows) assignSpots(LightProof::prove(scene, casts));
}

RasterScene::~RasterScene() {
  for (Batch& b : batches_) {
    gl_.DeleteBuffers(1, &b.vbo);
    if (b.elements) gl_.DeleteBuffers(1, &b.elements);
    if (b.colors) gl_.DeleteBuffers(1, &b.colors);
    gl_.DeleteVertexArrays(1, &b.vao);
  }
  for (unsigned image : images_) {
    if (image) gl_.DeleteTextures(1, &image);
  }
  if (areaPoints_.texture) gl_.DeleteTextures(1, &areaPoints_.texture);
  for (const auto& [key, program] : programs_) gl_.DeleteProgram(program);
}

void RasterScene::uploadTextures() {
  // Each image texture as a float RGB texture that texelFetch reads exactly
  // (no GL filtering: the shader filters as the tracer).
  for (const Texture& t : scene_.textures) {
    unsigned texture = 0;
    if (t.type == TextureType::kImage) {
      std::vector<glm::vec3> texels(static_cast<std::size_t>(t.image->width) * static_cast<std::size_t>(t.image->height));
      for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = t.image->texel(i);
      gl_.GenTextures(1, &texture);
      gl_.BindTexture(GL_TEXTURE_2D, texture);
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, t.image->width, t.image->height, 0, GL_RGB, GL_FLOAT, texels.data());
      if (gl_.GetError() != GL_NO_ERROR) {
        throw InputError("OpenGL: cannot hold a " + std::to_string(t.image->width) + " x " +
                         std::to_string(t.image->height) + " image texture (--mask all traces every pixel)");
      }
    }
    images_.push_back(texture);
  }
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
  batches_.push_back(std::move(b));
}

void RasterScene::uploadMeshes() {
  const Geometry& g = scene_.geometry;
  struct Mesh {
    std::vector<MeshVertex> vertices;
    std::vector<glm::vec3> colors;  // when the scene has vertex colours
    std::vector<std::uint32_t> prims;
  };
  std::map<std::uint32_t, Mesh> byMaterial;
  const bool colored = !g.colors().empty();
  for (std::uint32_t i = 0; i < g.triangles().size(); ++i) {
    const Triangle& t = g.triangles()[i];
    const std::uint32_t material = g.models()[t.model].material;
    const glm::vec3& face = g.faceNormals()[i];
    const auto object = static_cast<std::int32_t>(t.model + 1);
    Mesh& mesh = byMaterial[material];
    for (std::uint32_t v : t.v) {
      mesh.vertices.push_back({g.positions()[v], g.normals()[v], g.uvs()[v], face, object});
      if (colored) mesh.colors.push_back(g.colors()[v]);
    }
    mesh.prims.push_back(i);
  }
  for (auto& [material, mesh] : byMaterial) {
    newBatch(material, false, mesh.vertices.data(), mesh.vertices.size(), sizeof(MeshVertex));
    batches_.back().prims = std::move(mesh.prims);
    attribute(gl_, 0, 3, sizeof(MeshVertex), offsetof(MeshVertex, position));
    attribute(gl_, 1, 3, sizeof(MeshVertex), offsetof(MeshVertex, normal));
    attribute(gl_, 2, 2, sizeof(MeshVertex), offsetof(MeshVertex, uv));
    attribute(gl_, 3, 3, sizeof(MeshVertex), offsetof(MeshVertex, faceNormal));
    intAttribute(gl_, 4, sizeof(MeshVertex), offsetof(MeshVertex, object));
    if (colored) uploadColors(batches_.back(), mesh.colors);
  }
}

// A second buffer beside the batch's vertices: attribute 5, a colour each.
void RasterScene::uploadColors(Batch& batch, const std::vector<glm::vec3>& colors) {
  gl_.GenBuffers(1, &batch.colors);
  gl_.BindBuffer(GL_ARRAY_BUFFER, batch.colors);
  gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(colors.size() * sizeof(glm::vec3)), colors.data(),
                 GL_STATIC_DRAW);
  attribute(gl_, 5, 3, sizeof(glm::vec3), 0);
}

void RasterScene::uploadSpheres() {
  // The 12 triangles of a unit cube, corners in [-1, 1], each wound
  // counter-clockwise as seen from inside the cube.
  static const int kCube[36] = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                                2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
  struct Spheres {
    std::vector<SphereVertex> vertices;
    std::vector<Bounds3> boxes;
    std::vector<std::uint32_t> prims;
  };
  std::map<std::uint32_t, Spheres> byMaterial;
  const Geometry& g = scene_.geometry;
  const auto firstObject = static_cast<std::int32_t>(g.models().size() + 1);
  for (std::uint32_t i = 0; i < g.spheres().size(); ++i) {
    const Sphere& s = g.spheres()[i];
    Spheres& batch = byMaterial[s.material];
    // A box slightly larger than the sphere, so rasterization covers its edge.
    const float half = s.radius * 1.01f;
    batch.boxes.push_back(Bounds3{s.centre - glm::vec3(half), s.centre + glm::vec3(half)});
    batch.prims.push_back(static_cast<std::uint32_t>(g.triangles().size()) + i);
    for (int corner : kCube) {
      const glm::vec3 c(corner & 1 ? 1.0f : -1.0f, corner & 2 ? 1.0f : -1.0f, corner & 4 ? 1.0f : -1.0f);
      batch.vertices.push_back(
          {s.centre + half * c, glm::vec4(s.centre, s.radius), firstObject + static_cast<std::int32_t>(i)});
    }
  }
  for (auto& [material, spheres] : byMaterial) {
    newBatch(material, true, spheres.vertices.data(), spheres.vertices.size(), sizeof(SphereVertex));
    batches_.back().boxes = std::move(spheres.boxes);
    batches_.back().prims = std::move(spheres.prims);
    attribute(gl_, 0, 3, sizeof(SphereVertex), offsetof(SphereVertex, position));
    attribute(gl_, 1, 4, sizeof(SphereVertex), offsetof(SphereVertex, sphere));
    intAttribute(gl_, 2, sizeof(SphereVertex), offsetof(SphereVertex, object));
  }
}

void RasterScene::assignSpots(const LightProof& proof) {
  const Geometry& g = scene_.geometry;
  for (const ShadowSpot& spot : proof.spots) {
    const bool sphere = g.isSphere(spot.prim);
    const std::uint32_t material = sphere ? g.spheres()[spot.prim - g.triangles().size()].material
                                          : g.models()[g.triangles()[spot.prim].model].material;
    const auto batch = std::find_if(batches_.begin(), batches_.end(),
                                    [&](const Batch& b) { return b.material == material && b.spheres == sphere; });
    batch->spots.push_back(spot);
  }
}

RasterScene::Projection RasterScene::projection(const FrameSettings& frame) const {
  // The far plane just beyond the scene's farthest corner as seen from the eye.
  float far = 1.0f;
  if (!bounds_.empty()) {
    for (const glm::vec3& p : bounds_.corners()) far = std::max(far, glm::length(p - frame.camera.eye) * 1.01f);
  }
  const glm::mat4 view = glm::lookAt(frame.camera.eye, frame.camera.lookAt, frame.camera.up);
  // Reversed, infinite: clip w = the distance along the view axis, clip z =
  // near, so depth = near / distance (with GL_ZERO_TO_ONE); with
  // GL_DEPTH_CLAMP the near plane does not clip (the x and y planes still cut
  // what lies behind the eye).
  const float focal = 1.0f / std::tan(glm::radians(frame.camera.fovY) / 2.0f);
  glm::mat4 perspective(0.0f);
  perspective[0][0] = focal * static_cast<float>(frame.height) / static_cast<float>(frame.width);
  perspective[1][1] = focal;
  perspective[2][3] = -1.0f;
  perspective[3][2] = far * kNearShare;
  return {perspective * view, frame.camera.eye, far};
}

unsigned RasterScene::program(const ShaderVariant& variant) {
  const auto found = programs_.find(variant.key());
  if (found != programs_.end()) return found->second;
  const unsigned made = link(gl_, variant);
  programs_.emplace(variant.key(), made);
  return made;
}

TextureKind RasterScene::textureKind(int texture) const {
  if (texture < 0) return TextureKind::kNone;
  const Texture& t = scene_.textures[static_cast<std::size_t>(texture)];
  return t.type == TextureType::kChecker ? TextureKind::kChecker
         : t.type == TextureType::kSolid ? TextureKind::kNone
         : t.filter == ImageFilter::kBilinear ? TextureKind::kBilinear
                                              : TextureKind::kNearest;
}

ShaderVariant RasterScene::variantOf(const Batch& batch, const FrameSettings& frame, const MaskSettings& mask) const {
  ShaderVariant v;
  v.sphere = batch.spheres;
  const Material& m = scene_.materials[batch.material];
  v.traced = materialMasked(m, mask);
  if (v.traced) return v;
  v.texture = textureKind(m.texture);
  v.emits = plan_.materials[batch.material].emits;
  if (v.emits) v.emission = textureKind(m.emissionTexture);
  v.vertexColors = batch.colors != 0;
  v.lit = !scene_.lights.empty() && (m.diffuse > 0.0f || m.specular > 0.0f);
  v.specular = v.lit && m.specular > 0.0f;
  v.shadows = v.lit && shadows_ && !batch.spots.empty();
  v.srgb = frame.output.encoding == Encoding::kSrgb;
  v.spotLights = v.lit && spotLights_;
  v.directionalLights = v.lit && directionalLights_;
  v.field = field_ != nullptr;
  return v;
}

void RasterScene::setViewUniforms(unsigned program, const Projection& projection) {
  gl_.UseProgram(program);
  gl_.UniformMatrix4fv(gl_.GetUniformLocation(program, "uViewProjection"), 1, GL_FALSE,
                       glm::value_ptr(projection.viewProjection));
  gl_.Uniform1f(gl_.GetUniformLocation(program, "uFar"), projection.far);
  gl_.Uniform3fv(gl_.GetUniformLocation(program, "uEye"), 1, glm::value_ptr(projection.eye));
  gl_.Uniform3fv(gl_.GetUniformLocation(program, "uDepthAxis"), 1, glm::value_ptr(projection.depthAxis));
}

void RasterScene::setFrameUniforms(unsigned program, const FrameSettings& frame, const Projection& projection,
                                   const MaskSettings& mask) {
  setViewUniforms(program, projection);
  const auto at = [&](const char* name) { return gl_.GetUniformLocation(program, name); };
  gl_.Uniform1f(at("uExposureScale"), Encoder(frame.output).scale());
  gl_.Uniform1i(at("uMarkUndecided"), mask.rule == MaskRule::kAuto || mask.rule == MaskRule::kPerceptual ? 1 : 0);
  gl_.Uniform1i(at("uSelfShadowing"), plan_.shadows ? 1 : 0);
  setLightUniforms(program);
  gl_.Uniform1i(at("uImage"), kImageUnit);
  gl_.Uniform1i(at("uEmissionImage"), kEmissionUnit);
  shadowMaps_.setUniforms(program, kShadowMapUnit, punctualLights_.size(), shadows_);
  if (field_) field_->setUniforms(program, kFieldUnit);
}

void RasterScene::setLightUniforms(unsigned program) {
  const auto at = [&](const char* name) { return gl_.GetUniformLocation(program, name); };
  std::vector<glm::vec3> positions, colors, attenuations, directions;
  std::vector<glm::vec2> cones;
  std::vector<int> kinds;
  for (const Light& l : punctualLights_) {
    positions.push_back(l.position);
    colors.push_back(l.color);
    attenuations.push_back(l.attenuation);
    directions.push_back(l.direction);
    cones.emplace_back(l.cosInner, l.cosOuter);
    kinds.push_back(static_cast<int>(l.type));
  }
  gl_.Uniform1i(at("uLightCount"), static_cast<int>(positions.size()));
  if (!positions.empty()) {
    const auto n = static_cast<GLsizei>(positions.size());
    gl_.Uniform3fv(at("uLightPosition"), n, glm::value_ptr(positions[0]));
    gl_.Uniform3fv(at("uLightColor"), n, glm::value_ptr(colors[0]));
    gl_.Uniform3fv(at("uLightAttenuation"), n, glm::value_ptr(attenuations[0]));
    gl_.Uniform3fv(at("uLightDirection"), n, glm::value_ptr(directions[0]));
    gl_.Uniform2fv(at("uLightCone"), n, glm::value_ptr(cones[0]));
    gl_.Uniform1iv(at("uLightKind"), n, kinds.data());
  }
  gl_.Uniform1i(at("uAreaCount"), areaPoints_.count);
  gl_.Uniform1i(at("uAreaPoints"), kAreaPointsUnit);
}

void RasterScene::uploadAreaPoints(const FrameSettings& frame) {
  // Each area light as the points its unshadowed light is the sum of; a
  // sphere light as its centre, lighting every side (no normal).
  std::vector<glm::vec3> fields;
  const auto add = [&fields](const glm::vec3& position, const glm::vec3& colour, const glm::vec3& attenuation,
                             const glm::vec3& normal) { fields.insert(fields.end(), {position, colour, attenuation, normal}); };
  for (std::size_t i = 0; i < scene_.lights.size(); ++i) {
    const Light& l = scene_.lights[i];
    if (!softLight(l) || !plan_.lights[i]) continue;
    if (l.type == LightType::kSphere) {
      add(l.position, l.color, l.attenuation, glm::vec3(0.0f));
      continue;
    }
    const AreaLightPoints points(l, softLightSamples(l, frame.sampling.lightSamples));
    for (const glm::vec3& c : points.centres) add(c, points.color, l.attenuation, points.normal);
  }
  areaPoints_.count = static_cast<int>(fields.size() / kAreaPointFields);
  if (areaPoints_.count == 0) return;
  gl_.ActiveTexture(GL_TEXTURE0 + kAreaPointsUnit);
  uploadFloatTexels(gl_, areaPoints_.texture, std::move(fields), areaPoints_.count, kAreaPointFields,
                    kAreaPointsPerRow, "points of the area and sphere lights",
                    "fewer light samples, or --mask all traces them all");
  gl_.ActiveTexture(GL_TEXTURE0);
}

void RasterScene::useField(const IrradianceField& field) {
  const std::optional<EmitterPatches> patches = EmitterPatches::of(scene_, plan_, 0);
  if (!patches) {
    throw InputError("the hybrid frame cannot draw the emitters' light of this scene (more than " +
                     std::to_string(EmitterPatches::kMaxPatches) +
                     " emitting triangles, an emitting sphere or an emission texture): --mask all traces every pixel");
  }
  if (!field_) penumbra_.addEmitters(*patches);
  field_ = std::make_unique<FieldLight>(gl_, field, *patches);
}

bool RasterScene::objectLit(std::uint32_t object) const {
  // Objects are numbered from 1 (0: the background): the models, then the
  // spheres (uploadMeshes, uploadSpheres).
  const Geometry& g = scene_.geometry;
  const std::size_t models = g.models().size();
  if (object == 0 || object > models + g.spheres().size()) return false;
  const Material& m = scene_.materials[object <= models ? g.models()[object - 1].material
                                                        : g.spheres()[object - models - 1].material];
  return m.diffuse > 0.0f || m.specular > 0.0f;
}

RasterScene::PixelPoints RasterScene::pixelPoints(const FrameSettings& frame) const {
  return {Camera(frame.camera, frame.width, frame.height), glm::normalize(frame.camera.lookAt - frame.camera.eye),
          nearPlane(frame)};
}

glm::vec3 RasterScene::PixelPoints::at(int x, int y, float depth) const {
  const Ray ray = camera.generateRay({static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f});
  const float distance = near / depth;  // along the view axis
  return ray.o + (distance / glm::dot(ray.d, forward)) * ray.d;
}

void RasterScene::setUvTransform(int location, const std::optional<UvTransform>& transform) {
  const UvTransform t = transform.value_or(UvTransform{});
  const glm::mat3x2 columns(t.m[0], t.m[1], t.offset);
  gl_.UniformMatrix3x2fv(location, 1, GL_FALSE, glm::value_ptr(columns));
}

void RasterScene::setMaterialUniforms(unsigned program, const Material& m) {
  const auto at = [&](const char* name) { return gl_.GetUniformLocation(program, name); };
  gl_.Uniform3fv(at("uColor"), 1, glm::value_ptr(m.color));
  const glm::vec4 terms(m.ambient, m.diffuse, m.specular, m.shininess);
  gl_.Uniform4fv(at("uTerms"), 1, glm::value_ptr(terms));
  gl_.Uniform2f(at("uOtherLobes"), m.reflectivity, m.transparency);
  gl_.Uniform3fv(at("uEmission"), 1, glm::value_ptr(m.emission));
  if (m.emissionTexture >= 0) {
    const Texture& e = scene_.textures[static_cast<std::size_t>(m.emissionTexture)];
    setUvTransform(at("uEmissionTransform"), e.transform);
    gl_.Uniform2i(at("uEmissionWrap"), static_cast<int>(e.wrap[0]), static_cast<int>(e.wrap[1]));
    gl_.ActiveTexture(GL_TEXTURE0 + kEmissionUnit);
    gl_.BindTexture(GL_TEXTURE_2D, images_[static_cast<std::size_t>(m.emissionTexture)]);
  }
  if (m.texture < 0) return;
  const Texture& t = scene_.textures[static_cast<std::size_t>(m.texture)];
  setUvTransform(at("uImageTransform"), t.transform);
  gl_.Uniform2i(at("uImageWrap"), static_cast<int>(t.wrap[0]), static_cast<int>(t.wrap[1]));
  if (t.type == TextureType::kSolid) gl_.Uniform3fv(at("uColor"), 1, glm::value_ptr(t.colors[0]));
  gl_.Uniform3fv(at("uCheckerColor0"), 1, glm::value_ptr(t.colors[0]));
  gl_.Uniform3fv(at("uCheckerColor1"), 1, glm::value_ptr(t.colors[1]));
  gl_.Uniform1f(at("uCheckerScale"), t.scale);
  gl_.ActiveTexture(GL_TEXTURE0 + kImageUnit);
  gl_.BindTexture(GL_TEXTURE_2D, images_[static_cast<std::size_t>(m.texture)]);
}

bool RasterScene::prepareShadows(const MaskSettings& mask) {
  if (!rasterShadows(scene_, plan_, mask)) return false;
  if (shadowMaps_.size() != mask.shadowMap) {
    shadowMaps_.build(punctualLights_, punctualCasts_, bounds_, mask.shadowMap,
                      [this](const glm::mat4& vp, const glm::vec3& eye, float far, const glm::vec3& axis) {
                        drawDepth({vp, eye, far, axis});
                      });
  }
  return true;
}

void RasterScene::drawDepth(const Projection& projection) {
  gl_.Enable(GL_DEPTH_CLAMP);
  for (const Batch& b : batches_) {
    ShaderVariant v;
    v.sphere = b.spheres;
    v.traced = true;
    v.depthMap = true;
    setViewUniforms(program(v), projection);
    drawBatch(b, projection.eye);
  }
  gl_.BindVertexArray(0);
  gl_.UseProgram(0);
}

void RasterScene::drawBatch(const Batch& batch, const glm::vec3& eye, const Elements* elements) {
  const bool cull = batch.spheres && std::none_of(batch.boxes.begin(), batch.boxes.end(),
                                                  [&](const Bounds3& box) { return box.contains(eye); });
  if (cull) {
    gl_.Enable(GL_CULL_FACE);
    gl_.CullFace(GL_FRONT);  // the faces wound counter-clockwise from inside: the far ones
  }
  gl_.BindVertexArray(batch.vao);
  if (elements) {
    gl_.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(elements->count), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(elements->first * sizeof(std::uint32_t)));
  } else {
    gl_.DrawArrays(GL_TRIANGLES, 0, batch.vertices);
  }
  if (cull) gl_.Disable(GL_CULL_FACE);
}

void RasterScene::drawProgram(const Batch& batch, const ShaderVariant& variant, FrameDraw& draw,
                              const Elements* elements) {
  const unsigned p = program(variant);
  gl_.UseProgram(p);
  if (draw.framed.insert(variant.key()).second) setFrameUniforms(p, draw.frame, draw.projection, draw.mask);
  if (!variant.traced) setMaterialUniforms(p, scene_.materials[batch.material]);
  drawBatch(batch, draw.projection.eye, elements);
}

void RasterScene::drawShaded(Batch& batch, const ShaderVariant& variant, FrameDraw& draw) {
  ShaderVariant unshadowed = variant;
  unshadowed.shadows = false;
  const ShadowLayout layout =
      variant.shadows ? shadowLayout(batch.spots, draw.projection.viewProjection, draw.projection.eye,
                                     draw.frame.width, draw.frame.height)
                      : ShadowLayout{};
  if (layout.spotted.empty()) {
    drawProgram(batch, unshadowed, draw);
    return;
  }
  const std::vector<Elements> elements = binPrimitives(batch, layout, draw);
  if (elements[0].count > 0) drawProgram(batch, unshadowed, draw, &elements[0]);
  gl_.Enable(GL_SCISSOR_TEST);
  for (std::size_t i = 0; i < layout.rects.size(); ++i) {
    if (elements[i + 1].count == 0) continue;
    const ScissorRect& r = layout.rects[i];
    gl_.Scissor(r.x, r.y, r.width, r.height);
    drawProgram(batch, r.shadows ? variant : unshadowed, draw, &elements[i + 1]);
  }
  gl_.Disable(GL_SCISSOR_TEST);
}

std::vector<RasterScene::Elements> RasterScene::binPrimitives(Batch& batch, const ShadowLayout& layout,
                                                              const FrameDraw& draw) {
  const glm::vec2 size(static_cast<float>(draw.frame.width), static_cast<float>(draw.frame.height));
  const glm::mat4& vp = draw.projection.viewProjection;
  const Geometry& g = scene_.geometry;
  const std::uint32_t perPrim = batch.spheres ? 36 : 3;
  std::vector<std::uint32_t> free, spotted;  // batch-local indices
  for (std::uint32_t k = 0; k < batch.prims.size(); ++k) {
    const bool named = std::binary_search(layout.spotted.begin(), layout.spotted.end(), batch.prims[k]);
    (named ? spotted : free).push_back(k);
  }
  std::vector<WindowBox> boxes;
  for (std::uint32_t k : spotted) {
    if (batch.spheres) {
      boxes.push_back(windowBox(batch.boxes[k].corners(), vp, size));
    } else {
      const Triangle& t = g.triangles()[batch.prims[k]];
      const std::array<glm::vec3, 3> v{g.positions()[t.v[0]], g.positions()[t.v[1]], g.positions()[t.v[2]]};
      boxes.push_back(windowBox(v, vp, size));
    }
  }
  std::vector<std::uint32_t> indices;
  std::vector<Elements> ranges;
  const auto add = [&](std::uint32_t k) {
    for (std::uint32_t v = k * perPrim; v < (k + 1) * perPrim; ++v) indices.push_back(v);
  };
  for (std::uint32_t k : free) add(k);
  ranges.push_back({0, indices.size()});
  for (const ScissorRect& r : layout.rects) {
    const std::size_t first = indices.size();
    for (std::size_t i = 0; i < spotted.size(); ++i) {
      if (boxes[i].overlaps(r)) add(spotted[i]);
    }
    ranges.push_back({first, indices.size() - first});
  }
  gl_.BindVertexArray(batch.vao);
  if (!batch.elements) gl_.GenBuffers(1, &batch.elements);
  gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, batch.elements);
  gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
                 indices.data(), GL_STREAM_DRAW);
  return ranges;
}

double RasterScene::draw(const FrameSettings& frame, const MaskSettings& mask) {
  const Clock::time_point start = Clock::now();
  shadows_ = prepareShadows(mask);
  const double shadowMs = msSince(start);
  uploadAreaPoints(frame);
  target_.bind(frame.width, frame.height);
  gl_.Viewport(0, 0, frame.width, frame.height);
  const Encoder encoder(frame.output);
  const std::uint8_t background[3] = {encoder.byte(scene_.background.r), encoder.byte(scene_.background.g),
                                      encoder.byte(scene_.background.b)};
  target_.clear(background, backgroundMasked(scene_, mask) ? kMaskedPixel : kRasterPixel);
  gl_.Enable(GL_DEPTH_TEST);
  gl_.DepthFunc(GL_GREATER);
  gl_.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  gl_.Enable(GL_DEPTH_CLAMP);
  FrameDraw context{frame, mask, projection(frame), {}};
  // The masked batches first: their program is cheap, and the depth they
  // leave spares the fragments behind them the shading.
  for (const bool traced : {true, false}) {
    for (Batch& b : batches_) {
      const ShaderVariant variant = variantOf(b, frame, mask);
      if (variant.traced == traced) drawShaded(b, variant, context);
    }
  }
  gl_.ClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  gl_.Disable(GL_DEPTH_CLAMP);
  gl_.BindVertexArray(0);
  gl_.UseProgram(0);
  return shadowMs;
}

}  // namespace glint::gl
