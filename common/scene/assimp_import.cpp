#include "common/scene/assimp_import.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <memory>

#include <assimp/GltfMaterial.h>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <glm/common.hpp>

#include "common/base/error.h"
#include "common/scene/gltf_texture_transform.h"
#include "common/image/image_decode.h"

namespace glint {
namespace {

// One file's bytes, as Assimp reads them.
class ByteStream : public Assimp::IOStream {
 public:
  explicit ByteStream(std::string bytes) : bytes_(std::move(bytes)) {}
  size_t Read(void* buffer, size_t size, size_t count) override {
    if (size == 0) return 0;
    const size_t n = std::min(count, (bytes_.size() - at_) / size);
    std::memcpy(buffer, bytes_.data() + at_, n * size);
    at_ += n * size;
    return n;
  }
  size_t Write(const void*, size_t, size_t) override { return 0; }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const size_t size = bytes_.size();
    if (origin == aiOrigin_END ? offset > size : offset > size - (origin == aiOrigin_CUR ? at_ : 0)) {
      return aiReturn_FAILURE;
    }
    at_ = origin == aiOrigin_SET ? offset : origin == aiOrigin_CUR ? at_ + offset : size - offset;
    return aiReturn_SUCCESS;
  }
  size_t Tell() const override { return at_; }
  size_t FileSize() const override { return bytes_.size(); }
  void Flush() override {}

 private:
  std::string bytes_;
  size_t at_ = 0;
};

// Assimp's files come from the FileSource: nothing else is opened; the mesh
// file itself from the bytes already read. The first error of a read is
// kept (Assimp would only say "cannot open").
class SourceIo : public Assimp::IOSystem {
 public:
  SourceIo(FileSource& files, const std::string& path, std::string_view bytes, std::string place)
      : files_(files), path_(normalisePath(path)), bytes_(bytes), place_(std::move(place)) {}
  bool Exists(const char* path) const override { return files_.has(normalisePath(path)); }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* path, const char* mode) override {
    if (std::strchr(mode, 'w') || std::strchr(mode, 'a')) return nullptr;
    const std::string wanted = normalisePath(path);
    if (wanted == path_) return new ByteStream(std::string(bytes_));
    try {
      return new ByteStream(files_.readForImport(wanted, place_));
    } catch (const InputError& e) {
      if (error_.empty()) error_ = e.what();
      return nullptr;
    }
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }
  const std::string& error() const { return error_; }

 private:
  FileSource& files_;
  std::string path_;
  std::string_view bytes_;
  std::string place_;
  std::string error_;
};

// The Phong terms an imported material gets (docs/scene-format.md): scene
// 1's ambient, so that a shadowed side is not black, the rest diffuse.
constexpr float kImportedAmbient = 0.1f;
constexpr float kImportedDiffuse = 0.9f;
constexpr float kHighlightAtZeroRoughness = 0.5f;  // r_S of a perfectly smooth surface
constexpr float kMaxShininess = 1000.0f;

// A glTF roughness -> Phong's highlight: r_S fading to 0 at roughness 1,
// and the Blinn-Phong exponent of the same lobe width, h = 2 / a^2 - 2 with
// a = roughness^2 (Walter et al., "Microfacet Models for Refraction through
// Rough Surfaces", EGSR 2007).
void highlightFromRoughness(float roughness, Material& out) {
  const float r = std::clamp(roughness, 0.0f, 1.0f);
  const float a = std::max(r * r, 1e-3f);
  out.specular = kHighlightAtZeroRoughness * (1.0f - r);
  out.shininess = std::clamp(2.0f / (a * a) - 2.0f, 1.0f, kMaxShininess);
}

// Assimp's material -> Glint's.
Material toMaterial(const aiMaterial& m) {
  Material out;
  out.ambient = kImportedAmbient;
  out.diffuse = kImportedDiffuse;
  aiString name;
  if (m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) out.name = name.C_Str();
  aiColor4D c;
  if (m.Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS || m.Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) {
    out.color = {c.r, c.g, c.b};
  }
  aiColor3D e;
  if (m.Get(AI_MATKEY_COLOR_EMISSIVE, e) == AI_SUCCESS) out.emission = {e.r, e.g, e.b};  // checkImportedModel
  float opacity = 1.0f, metallic = 0.0f, roughness = 1.0f;
  m.Get(AI_MATKEY_OPACITY, opacity);
  out.transparency = std::clamp(1.0f - opacity, 0.0f, 1.0f);
  if (m.Get(AI_MATKEY_METALLIC_FACTOR, metallic) == AI_SUCCESS) {
    m.Get(AI_MATKEY_ROUGHNESS_FACTOR, roughness);
    out.reflectivity = std::clamp(metallic * (1.0f - roughness), 0.0f, 1.0f);
    if (out.reflectivity > 0.0f) out.roughness = std::clamp(roughness, 0.0f, 1.0f);
    highlightFromRoughness(roughness, out);
  }
  return out;
}

// The KHR_texture_transform Assimp's glTF importer read (its transform
// turns the other way about the image's centre, with v up, so it moved the
// offset: undone here).
KhrTextureTransform khrTransform(const aiUVTransform& uv) {
  KhrTextureTransform t;
  t.scale = {uv.mScaling.x, uv.mScaling.y};
  t.rotation = -uv.mRotation;
  const double c = std::cos(t.rotation), s = std::sin(t.rotation);
  t.offset.x = uv.mTranslation.x - 0.5 * t.scale.x * (1.0 - c + s);
  t.offset.y = 1.0 - t.scale.y + 0.5 * t.scale.y * (s + c - 1.0) - uv.mTranslation.y;
  return t;
}

// The texture's sampler (glTF's wrapS, wrapT and magFilter, as Assimp's
// importer keeps them): its wrap modes, and bilinear for a LINEAR
// magnification (Glint reads one filter both ways and has no mip maps, so
// the min filter is not read); none given: repeat, nearest.
void readSampler(const aiMaterial& m, aiTextureType type, Texture& tex) {
  const auto wrapOf = [](int mode) {
    return mode == aiTextureMapMode_Mirror  ? TextureWrap::kMirroredRepeat
           : mode == aiTextureMapMode_Clamp ? TextureWrap::kClampToEdge
                                            : TextureWrap::kRepeat;
  };
  int u = aiTextureMapMode_Wrap, v = aiTextureMapMode_Wrap;
  m.Get(AI_MATKEY_MAPPINGMODE_U(type, 0), u);
  m.Get(AI_MATKEY_MAPPINGMODE_V(type, 0), v);
  tex.wrap = {wrapOf(u), wrapOf(v)};
  constexpr int kGlLinear = 9729;  // glTF's (OpenGL's) LINEAR
  int mag = 0;
  if (m.Get(AI_MATKEY_GLTF_MAPPINGFILTER_MAG(type, 0), mag) == AI_SUCCESS && mag == kGlLinear) {
    tex.filter = ImageFilter::kBilinear;
  }
}

// The material's texture of the first of `types` it has, from a file
// beside the mesh or embedded in it; -1 without one, or when its file is
// missing.
int readTexture(const aiScene& scene, const aiMaterial& m, std::initializer_list<aiTextureType> types,
                FileSource& files, const std::string& path, const std::string& place, SceneBudget& budget,
                MeshModel& model) {
  aiString uri;
  const auto type = std::find_if(types.begin(), types.end(),
                                 [&](aiTextureType t) { return m.GetTexture(t, 0, &uri) == AI_SUCCESS; });
  if (type == types.end()) return -1;
  const std::string texPlace = place + " (texture " + uri.C_Str() + ")";
  std::string bytes;
  if (const aiTexture* embedded = scene.GetEmbeddedTexture(uri.C_Str())) {
    if (embedded->mHeight != 0) throw InputError(texPlace + ": an embedded texture must be an image file's bytes");
    bytes.assign(reinterpret_cast<const char*>(embedded->pcData), embedded->mWidth);
  } else {
    const std::string texPath = siblingPath(path, uri.C_Str());
    if (!files.has(texPath)) {
      model.warnings.push_back("'" + path + "' names the texture '" + texPath +
                               "', which is missing; the material's colour is used");
      return -1;
    }
    bytes = files.readForImport(texPath, texPlace);
  }
  Texture tex;
  tex.type = TextureType::kImage;
  tex.image = std::make_shared<Image>(decodeImage(bytes, texPlace, budget));
  aiUVTransform uv;
  if (m.Get(AI_MATKEY_UVTRANSFORM(*type, 0), uv) == AI_SUCCESS) tex.transform = glintUvTransform(khrTransform(uv));
  readSampler(m, *type, tex);
  model.textures.push_back(std::move(tex));
  return static_cast<int>(model.textures.size()) - 1;
}

// One Assimp mesh's triangles (its points and lines left out).
MeshInput toMesh(const aiMesh& m) {
  MeshInput mesh;
  mesh.material = m.mMaterialIndex;
  mesh.positions.reserve(m.mNumVertices);
  for (unsigned i = 0; i < m.mNumVertices; ++i) {
    mesh.positions.emplace_back(m.mVertices[i].x, m.mVertices[i].y, m.mVertices[i].z);
    if (m.HasNormals()) mesh.normals.emplace_back(m.mNormals[i].x, m.mNormals[i].y, m.mNormals[i].z);
    if (m.HasTextureCoords(0)) mesh.uvs.emplace_back(m.mTextureCoords[0][i].x, m.mTextureCoords[0][i].y);
    if (m.HasVertexColors(0)) mesh.colors.emplace_back(m.mColors[0][i].r, m.mColors[0][i].g, m.mColors[0][i].b);
  }
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiFace& face = m.mFaces[f];
    if (face.mNumIndices != 3) continue;
    mesh.indices.insert(mesh.indices.end(), face.mIndices, face.mIndices + 3);
  }
  return mesh;
}

}  // namespace

MeshModel importWithAssimp(FileSource& files, const std::string& path, std::string_view bytes,
                           const std::string& place, SceneBudget& budget) {
  Assimp::Importer importer;
  auto* io = new SourceIo(files, path, bytes, place);
  importer.SetIOHandler(io);  // the importer owns it
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                                     aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (!scene || !scene->mRootNode) {
    const std::string why = !io->error().empty()
                                ? io->error()
                                : place + ": '" + path + "' cannot be imported: " + importer.GetErrorString();
    throw InputError(why);
  }
  MeshModel model;
  std::size_t triangles = 0, vertices = 0;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    MeshInput mesh = toMesh(*scene->mMeshes[i]);
    if (mesh.indices.empty()) continue;
    triangles += mesh.indices.size() / 3;
    vertices += mesh.positions.size();
    model.meshes.push_back(std::move(mesh));
  }
  if (triangles == 0) throw InputError(place + ": '" + path + "' holds no triangle (points or lines only?)");
  if (triangles > budget.limits().maxTriangles || vertices > budget.limits().maxVertices) {
    throw InputError(place + ": '" + path + "' has more triangles or vertices than the limits (" +
                     std::to_string(budget.limits().maxTriangles) + ", " + std::to_string(budget.limits().maxVertices) +
                     ")");
  }
  for (unsigned i = 0; i < scene->mNumMaterials; ++i) {
    Material m = toMaterial(*scene->mMaterials[i]);
    const aiMaterial& from = *scene->mMaterials[i];
    m.texture = readTexture(*scene, from, {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}, files, path, place,
                            budget, model);  // times m.color
    if (m.emission != glm::vec3(0.0f)) {
      m.emissionTexture = readTexture(*scene, from, {aiTextureType_EMISSIVE}, files, path, place, budget, model);
    }
    model.materials.push_back(std::move(m));
  }
  return model;
}

}  // namespace glint
