#include "common/scene/mesh_blob.h"

#include <cmath>
#include <cstring>
#include <type_traits>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "common/base/error.h"
#include "common/math/finite.h"

namespace glint {
namespace {

constexpr std::string_view kMagic = "GLINTMSH";
constexpr std::uint32_t kVersion = 4;

class Writer {
 public:
  template <typename T>
  void put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  template <typename T>
  void putArray(const std::vector<T>& values) {
    if (values.empty()) return;
    out_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  void putString(std::string_view s) {
    put(static_cast<std::uint32_t>(s.size()));
    out_.append(s);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

// Reads what is there; asking for more than remains is an InputError.
class Reader {
 public:
  Reader(std::string_view bytes, const std::string& place) : bytes_(bytes), place_(place) {}

  template <typename T>
  T get() {
    T value;
    std::memcpy(&value, need(sizeof value, "a field"), sizeof value);
    return value;
  }
  // `count` elements, checked against the bytes left before allocating.
  template <typename T>
  std::vector<T> getArray(std::size_t count, const char* what) {
    if (count > remaining() / sizeof(T)) fail(std::string("announces more ") + what + " than it holds");
    if (count == 0) return {};
    std::vector<T> values(count);
    std::memcpy(values.data(), need(count * sizeof(T), what), count * sizeof(T));
    return values;
  }
  std::string getString() {
    const auto n = get<std::uint32_t>();
    return std::string(need(n, "a name"), n);
  }
  std::size_t remaining() const { return bytes_.size() - at_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(place_ + ": the imported mesh " + what);
  }

 private:
  const char* need(std::size_t n, const char* what) {
    if (n > remaining()) fail(std::string("ends inside ") + what);
    const char* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
  const std::string& place_;
};

void writeMaterial(Writer& w, const Material& m) {
  w.putString(m.name);
  w.put(m.color);
  w.put(static_cast<std::int32_t>(m.texture));
  w.put(m.emission);
  w.put(static_cast<std::int32_t>(m.emissionTexture));
  for (const float v : {m.ambient, m.diffuse, m.specular, m.shininess, m.reflectivity, m.roughness, m.transparency, m.ior}) {
    w.put(v);
  }
  w.put(static_cast<std::uint8_t>(m.raytrace));
}

Material readMaterial(Reader& r, std::size_t textures) {
  Material m;
  m.name = r.getString();
  m.color = r.get<glm::vec3>();
  m.texture = r.get<std::int32_t>();
  m.emission = r.get<glm::vec3>();
  m.emissionTexture = r.get<std::int32_t>();
  for (const int t : {m.texture, m.emissionTexture}) {
    if (t < -1 || t >= static_cast<std::int64_t>(textures)) r.fail("names a texture it does not hold");
  }
  for (float* v : {&m.ambient, &m.diffuse, &m.specular, &m.shininess, &m.reflectivity, &m.roughness, &m.transparency, &m.ior}) {
    *v = r.get<float>();
  }
  const auto rule = r.get<std::uint8_t>();
  if (rule > static_cast<std::uint8_t>(RaytraceRule::kNever)) r.fail("has an unknown raytrace rule");
  m.raytrace = static_cast<RaytraceRule>(rule);
  return m;
}

void writeLight(Writer& w, const Light& l) {
  w.put(static_cast<std::uint8_t>(l.type));
  for (const glm::vec3& v : {l.position, l.direction, l.color, l.attenuation}) w.put(v);
  w.put(l.cosInner);
  w.put(l.cosOuter);
}

// A light as the glTF reader makes them: point, spot or directional, finite,
// a unit direction, cones in order and an attenuation that is not zero.
Light readLight(Reader& r) {
  Light l;
  const auto type = r.get<std::uint8_t>();
  l.type = static_cast<LightType>(type);
  if (type > static_cast<std::uint8_t>(LightType::kDirectional) || l.type == LightType::kArea) {
    r.fail("has a light of an unknown type");
  }
  for (glm::vec3* v : {&l.position, &l.direction, &l.color, &l.attenuation}) *v = r.get<glm::vec3>();
  l.cosInner = r.get<float>();
  l.cosOuter = r.get<float>();
  const bool finite = std::isfinite(l.cosInner) && std::isfinite(l.cosOuter) && allFinite(l.position) &&
                      allFinite(l.color) && allFinite(l.attenuation);
  const float length = glm::length(l.direction);
  if (!finite || !(std::abs(length - 1.0f) < 1e-3f)) r.fail("has a light that is not finite or not aimed");
  if (!(l.cosOuter >= 0.0f && l.cosOuter <= l.cosInner && l.cosInner <= 1.0f)) r.fail("has a spot's cones out of order");
  if (glm::any(glm::lessThan(l.attenuation, glm::vec3(0.0f))) || l.attenuation == glm::vec3(0.0f)) {
    r.fail("has a light's attenuation below zero or zero");
  }
  return l;
}

Texture readTexture(Reader& r, const std::string& place, SceneBudget& budget) {
  const auto width = r.get<std::uint32_t>(), height = r.get<std::uint32_t>();
  const auto filter = r.get<std::uint8_t>();
  if (filter > static_cast<std::uint8_t>(ImageFilter::kBilinear)) r.fail("has an unknown texture filter");
  std::array<TextureWrap, 2> wrap{};
  for (TextureWrap& w : wrap) {
    const auto mode = r.get<std::uint8_t>();
    if (mode > static_cast<std::uint8_t>(TextureWrap::kClampToEdge)) r.fail("has an unknown texture wrap mode");
    w = static_cast<TextureWrap>(mode);
  }
  if (width == 0 || height == 0 || std::size_t{width} * height > budget.limits().maxTexturePixels) {
    r.fail("has a texture of no pixels or over the limit of " + std::to_string(budget.limits().maxTexturePixels));
  }
  budget.chargeImage(static_cast<int>(width), static_cast<int>(height), place, Image::kBytesPerTexel);
  auto image = std::make_shared<Image>();
  image->width = static_cast<int>(width);
  image->height = static_cast<int>(height);
  image->rgb = r.getArray<std::uint8_t>(std::size_t{width} * height * 3, "texels");
  Texture t;
  t.type = TextureType::kImage;
  t.filter = static_cast<ImageFilter>(filter);
  t.wrap = wrap;
  t.image = std::move(image);
  if (r.get<std::uint8_t>() != 0) t.transform = UvTransform{r.get<glm::mat2>(), r.get<glm::vec2>()};
  return t;
}

MeshInput readMesh(Reader& r, std::size_t materials, const LoadLimits& limits) {
  MeshInput mesh;
  mesh.material = r.get<std::uint32_t>();
  if (mesh.material >= materials) r.fail("has a mesh with a material it does not hold");
  const auto vertices = r.get<std::uint32_t>();
  if (vertices > limits.maxVertices) r.fail("has more vertices than the limit");
  const bool normals = r.get<std::uint8_t>() != 0, uvs = r.get<std::uint8_t>() != 0;
  const bool colors = r.get<std::uint8_t>() != 0;
  mesh.positions = r.getArray<glm::vec3>(vertices, "positions");
  if (normals) mesh.normals = r.getArray<glm::vec3>(vertices, "normals");
  if (uvs) mesh.uvs = r.getArray<glm::vec2>(vertices, "uvs");
  if (colors) mesh.colors = r.getArray<glm::vec3>(vertices, "colors");
  const auto indices = r.get<std::uint32_t>();
  if (indices % 3 != 0) r.fail("has a mesh whose index count is not a multiple of 3");
  mesh.indices = r.getArray<std::uint32_t>(indices, "indices");
  for (const std::uint32_t i : mesh.indices) {
    if (i >= vertices) r.fail("has an index past its vertices");
  }
  return mesh;
}

}  // namespace

std::string encodeMeshBlob(const MeshModel& model) {
  Writer w;
  for (const char c : kMagic) w.put(c);
  w.put(kVersion);
  w.put(static_cast<std::uint32_t>(model.textures.size()));
  for (const Texture& t : model.textures) {
    w.put(static_cast<std::uint32_t>(t.image->width));
    w.put(static_cast<std::uint32_t>(t.image->height));
    w.put(static_cast<std::uint8_t>(t.filter));
    for (const TextureWrap mode : t.wrap) w.put(static_cast<std::uint8_t>(mode));
    w.putArray(t.image->rgb);
    w.put(static_cast<std::uint8_t>(t.transform.has_value()));
    if (t.transform) {
      w.put(t.transform->m);
      w.put(t.transform->offset);
    }
  }
  w.put(static_cast<std::uint32_t>(model.materials.size()));
  for (const Material& m : model.materials) writeMaterial(w, m);
  w.put(static_cast<std::uint32_t>(model.meshes.size()));
  for (const MeshInput& mesh : model.meshes) {
    w.put(mesh.material);
    w.put(static_cast<std::uint32_t>(mesh.positions.size()));
    w.put(static_cast<std::uint8_t>(!mesh.normals.empty()));
    w.put(static_cast<std::uint8_t>(!mesh.uvs.empty()));
    w.put(static_cast<std::uint8_t>(!mesh.colors.empty()));
    w.putArray(mesh.positions);
    w.putArray(mesh.normals);
    w.putArray(mesh.uvs);
    w.putArray(mesh.colors);
    w.put(static_cast<std::uint32_t>(mesh.indices.size()));
    w.putArray(mesh.indices);
  }
  w.put(static_cast<std::uint8_t>(model.camera.has_value()));
  if (model.camera) {
    w.put(model.camera->eye);
    w.put(model.camera->lookAt);
    w.put(model.camera->up);
    w.put(model.camera->fovY);
  }
  w.put(static_cast<std::uint32_t>(model.lights.size()));
  for (const Light& l : model.lights) writeLight(w, l);
  return w.take();
}

MeshModel decodeMeshBlob(std::string_view bytes, const std::string& place, SceneBudget& budget) {
  Reader r(bytes, place);
  if (bytes.substr(0, kMagic.size()) != kMagic) {
    throw InputError(place + ": a glTF or PLY mesh reaches a server imported by the client; these bytes are not "
                             "an imported mesh (glintd does not run importers on what a peer sends)");
  }
  r.getArray<char>(kMagic.size(), "the magic");
  if (r.get<std::uint32_t>() != kVersion) r.fail("is of another version");
  MeshModel model;
  const auto textures = r.get<std::uint32_t>();
  for (std::uint32_t i = 0; i < textures; ++i) model.textures.push_back(readTexture(r, place, budget));
  const auto materials = r.get<std::uint32_t>();
  if (materials > r.remaining()) r.fail("announces more materials than it holds");
  for (std::uint32_t i = 0; i < materials; ++i) model.materials.push_back(readMaterial(r, textures));
  const auto meshes = r.get<std::uint32_t>();
  if (meshes > r.remaining()) r.fail("announces more meshes than it holds");
  for (std::uint32_t i = 0; i < meshes; ++i) model.meshes.push_back(readMesh(r, materials, budget.limits()));
  if (r.get<std::uint8_t>() != 0) {  // the camera is checked where the scene takes it
    CameraSpec camera;
    camera.eye = r.get<glm::vec3>();
    camera.lookAt = r.get<glm::vec3>();
    camera.up = r.get<glm::vec3>();
    camera.fovY = r.get<float>();
    model.camera = camera;
  }
  const auto lights = r.get<std::uint32_t>();
  if (lights > r.remaining()) r.fail("announces more lights than it holds");
  for (std::uint32_t i = 0; i < lights; ++i) model.lights.push_back(readLight(r));
  if (r.remaining() != 0) r.fail("has bytes after its last mesh");
  checkImportedModel(model, place);
  return model;
}

}  // namespace glint
