#include "common/obj_load.h"

#include <map>
#include <sstream>
#include <tuple>

#include <tiny_obj_loader.h>

#include "common/error.h"
#include "common/image_io.h"

namespace glint {
namespace {

// The first "mtllib NAME" of the file, or "" (tinyobjloader's string parser
// ignores mtllib, so the loader reads the library itself).
std::string mtllibName(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword;
    if (words >> keyword && keyword == "mtllib") {
      std::string name;
      std::getline(words >> std::ws, name);
      while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
      return name;
    }
  }
  return "";
}

float mean(const float c[3]) { return (c[0] + c[1] + c[2]) / 3.0f; }

// MTL illumination models 3 to 7 trace reflections (3, 4, 5) and
// refractions (6, 7); below 3 Ks is only the highlight.
bool mtlReflects(int illum) { return illum >= 3 && illum <= 7; }

// MTL -> Glint: Kd is the surface colour C (or map_Kd the texture) with r_D
// = 1, so that C r_D = Kd; r_A and r_S are the means of Ka and Ks; Ns is h;
// Ni the index; d (or 1 - Tr) the opacity; under illum 3 to 7 the mean of
// Ks is also the reflectivity.
Material toMaterial(const tinyobj::material_t& m) {
  Material out;
  out.name = m.name;
  out.color = {m.diffuse[0], m.diffuse[1], m.diffuse[2]};
  out.ambient = mean(m.ambient);
  out.diffuse = 1.0f;
  out.specular = mean(m.specular);
  out.shininess = m.shininess > 0.0f ? m.shininess : 1.0f;
  out.ior = m.ior > 0.0f ? m.ior : 1.0f;
  out.transparency = std::clamp(1.0f - m.dissolve, 0.0f, 1.0f);
  if (mtlReflects(m.illum)) out.reflectivity = std::clamp(mean(m.specular), 0.0f, 1.0f);
  return out;
}

struct VertexKey {
  int v, n, t;
  auto operator<=>(const VertexKey&) const = default;
};

// Why a text cannot be an OBJ at all, or "".
std::string notObjText(const std::string& text) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) return "is empty";
  const bool bom16 = text.size() >= 2 && ((text[0] == '\xff' && text[1] == '\xfe') || (text[0] == '\xfe' && text[1] == '\xff'));
  if (bom16 || text.find('\0') != std::string::npos) {
    return "is not a text file in ASCII or UTF-8 (UTF-16, or binary); save it as UTF-8";
  }
  return "";
}

// The OBJ (and, when materials are wanted, its mtllib, whose path goes to
// `mtlPath`) parsed by tinyobjloader; a missing mtllib is a warning.
tinyobj::ObjReader parseObj(FileSource& files, const std::string& path, const std::string& place,
                            const LoadLimits& limits, bool withMaterials, std::vector<std::string>& warnings,
                            std::string& mtlPath) {
  const std::string text = files.read(path, place);
  if (const std::string why = notObjText(text); !why.empty()) throw InputError(place + ": '" + path + "' " + why);
  std::string mtl;
  const std::string lib = mtllibName(text);
  if (withMaterials && !lib.empty()) {
    const std::string libPath = siblingPath(path, lib);
    if (files.has(libPath)) {
      mtl = files.read(libPath, place + " (mtllib " + lib + ")");
      mtlPath = libPath;
    } else {
      warnings.push_back("'" + path + "' names the material library '" + libPath +
                         "', which is missing; its faces get the default material");
    }
  }
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, mtl, config)) {
    throw InputError(place + ": '" + path + "' is not a valid OBJ file: " + reader.Error());
  }
  const std::size_t positions = reader.GetAttrib().vertices.size() / 3;
  if (positions > limits.maxVertices) {
    throw InputError(place + ": '" + path + "' has " + std::to_string(positions) +
                     " vertices, over the limit of " + std::to_string(limits.maxVertices));
  }
  return reader;
}

// The materials of the MTL file at `mtlPath`, each map_Kd (relative to the
// MTL file) decoded as the material's texture; a missing texture is a
// warning, and the material keeps its Kd colour.
void readMaterials(const tinyobj::ObjReader& reader, FileSource& files, const std::string& mtlPath,
                   const std::string& place, SceneBudget& budget, MeshModel& model) {
  for (const tinyobj::material_t& m : reader.GetMaterials()) {
    Material mat = toMaterial(m);
    const std::string texPath = m.diffuse_texname.empty() ? "" : siblingPath(mtlPath, m.diffuse_texname);
    if (!texPath.empty() && !files.has(texPath)) {
      model.warnings.push_back("'" + mtlPath + "' names the texture '" + texPath + "' (map_Kd of material " +
                               m.name + "), which is missing; the material's Kd colour is used");
    } else if (!texPath.empty()) {
      const std::string texPlace = place + " (map_Kd of material " + m.name + ")";
      Texture tex;
      tex.type = TextureType::kImage;
      tex.image = std::make_shared<Image>(decodeImage(files.read(texPath, texPlace), texPlace, budget));
      mat.texture = static_cast<int>(model.textures.size());
      mat.color = glm::vec3(1.0f);
      model.textures.push_back(std::move(tex));
    }
    model.materials.push_back(std::move(mat));
  }
}

// The faces of one material become one mesh; a corner (position, normal, uv)
// seen before reuses its vertex.
class FaceGrouper {
 public:
  explicit FaceGrouper(const tinyobj::attrib_t& attrib) : attrib_(attrib) {}

  // False when the corner refers to data the file does not have.
  bool addCorner(int material, const tinyobj::index_t& idx) {
    if (idx.vertex_index < 0 || static_cast<std::size_t>(idx.vertex_index) >= attrib_.vertices.size() / 3 ||
        idx.normal_index >= static_cast<int>(attrib_.normals.size() / 3) ||
        idx.texcoord_index >= static_cast<int>(attrib_.texcoords.size() / 2)) {
      return false;
    }
    MeshInput& group = groups_[material];
    const VertexKey key{idx.vertex_index, idx.normal_index, idx.texcoord_index};
    auto [it, inserted] = vertexMaps_[material].try_emplace(key, static_cast<std::uint32_t>(group.positions.size()));
    if (inserted) {
      const auto v = static_cast<std::size_t>(idx.vertex_index);
      group.positions.emplace_back(attrib_.vertices[3 * v], attrib_.vertices[3 * v + 1], attrib_.vertices[3 * v + 2]);
      const auto n = static_cast<std::size_t>(std::max(idx.normal_index, 0));
      group.normals.push_back(idx.normal_index >= 0 ? glm::vec3(attrib_.normals[3 * n], attrib_.normals[3 * n + 1],
                                                                attrib_.normals[3 * n + 2])
                                                    : glm::vec3(0.0f));
      const auto t = static_cast<std::size_t>(std::max(idx.texcoord_index, 0));
      group.uvs.push_back(idx.texcoord_index >= 0
                              ? glm::vec2(attrib_.texcoords[2 * t], attrib_.texcoords[2 * t + 1])
                              : glm::vec2(0.0f));
      auto [c, fresh] = complete_.try_emplace(material, true);
      c->second = c->second && idx.normal_index >= 0;
    }
    group.indices.push_back(it->second);
    return true;
  }

  // The meshes; a mesh some of whose corners lack a normal gets its normals
  // from the faces instead.
  void finish(MeshModel& model) {
    for (auto& [mat, group] : groups_) {
      if (!complete_[mat]) group.normals.clear();
      group.material = static_cast<std::uint32_t>(mat);
      model.meshes.push_back(std::move(group));
    }
  }
  bool uses(int material) const { return groups_.count(material) > 0; }

 private:
  const tinyobj::attrib_t& attrib_;
  std::map<int, MeshInput> groups_;
  std::map<int, std::map<VertexKey, std::uint32_t>> vertexMaps_;
  std::map<int, bool> complete_;  // every corner has a normal
};

}  // namespace

MeshModel loadObj(FileSource& files, const std::string& path, const std::string& place, SceneBudget& budget,
                 bool withMaterials) {
  const LoadLimits& limits = budget.limits();
  MeshModel model;
  std::string mtlPath;
  const tinyobj::ObjReader reader = parseObj(files, path, place, limits, withMaterials, model.warnings, mtlPath);
  if (!mtlPath.empty()) readMaterials(reader, files, mtlPath, place, budget, model);
  // Faces without a material (or all faces, without MTL) use a default one.
  const int defaultMaterial = static_cast<int>(model.materials.size());
  FaceGrouper grouper(reader.GetAttrib());
  std::size_t triangles = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& mesh = shape.mesh;
    for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const auto faceError = [&](const char* what) {
        return InputError(place + ": '" + path + "' face " + std::to_string(f) + " of '" + shape.name + "' " + what);
      };
      if (mesh.num_face_vertices[f] != 3) throw faceError("could not be triangulated");
      if (++triangles > limits.maxTriangles) {
        throw InputError(place + ": '" + path + "' has more triangles than the limit of " +
                         std::to_string(limits.maxTriangles));
      }
      int mat = withMaterials && f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      if (mat < 0 || mat >= defaultMaterial) mat = defaultMaterial;
      for (std::size_t k = 0; k < 3; ++k) {
        if (!grouper.addCorner(mat, mesh.indices[3 * f + k])) {
          throw faceError("refers to a vertex, normal or uv that the file does not have");
        }
      }
    }
  }
  if (triangles == 0) {
    throw InputError(place + ": '" + path + "' holds no triangle (" +
                     std::to_string(reader.GetAttrib().vertices.size() / 3) +
                     " vertices, no faces: points or lines only?); a mesh needs faces (f lines)");
  }
  grouper.finish(model);
  if (grouper.uses(defaultMaterial)) model.materials.push_back(Material{});
  return model;
}

}  // namespace glint
