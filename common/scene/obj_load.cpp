#include "common/scene/obj_load.h"

#include <algorithm>
#include <array>
#include <map>
#include <unordered_map>
#include <tuple>

#include <glm/common.hpp>

#include "common/base/array_hash.h"
#include "common/base/error.h"
#include "common/base/heap_tuning.h"
#include "common/scene/obj_faces.h"

namespace glint {
namespace {

// The first "mtllib NAME" of the file, or "" (tinyobjloader's string parser
// ignores mtllib, so the loader reads the library itself). Found with find()
// rather than line by line: a large mesh's text is tens of megabytes.
std::string mtllibName(const std::string& text) {
  for (std::size_t at = text.find("mtllib"); at != std::string::npos; at = text.find("mtllib", at + 6)) {
    const std::size_t lineStart = text.find_last_not_of(" \t", at == 0 ? std::string::npos : at - 1);
    if (at != 0 && lineStart != std::string::npos && text[lineStart] != '\n' && text[lineStart] != '\r') continue;
    if (at + 6 < text.size() && text[at + 6] != ' ' && text[at + 6] != '\t') continue;
    const std::size_t start = text.find_first_not_of(" \t", at + 6);
    if (start == std::string::npos) return "";
    std::string name = text.substr(start, text.find_first_of("\r\n", start) - start);
    while (!name.empty() && (name.back() == ' ' || name.back() == '\t')) name.pop_back();
    return name;
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
// Ks is also the reflectivity; Ke is the emission.
Material toMaterial(const tinyobj::material_t& m) {
  Material out;
  out.name = m.name;
  out.color = {m.diffuse[0], m.diffuse[1], m.diffuse[2]};
  out.emission = glm::max(glm::vec3(m.emission[0], m.emission[1], m.emission[2]), glm::vec3(0.0f));
  out.ambient = mean(m.ambient);
  out.diffuse = 1.0f;
  out.specular = mean(m.specular);
  out.shininess = m.shininess > 0.0f ? m.shininess : 1.0f;
  out.ior = m.ior > 0.0f ? m.ior : 1.0f;
  out.transparency = std::clamp(1.0f - m.dissolve, 0.0f, 1.0f);
  if (mtlReflects(m.illum)) out.reflectivity = std::clamp(mean(m.specular), 0.0f, 1.0f);
  return out;
}

// Why a text cannot be an OBJ at all, or "".
std::string notObjText(const std::string& text) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) return "is empty";
  const bool bom16 = text.size() >= 2 && ((text[0] == '\xff' && text[1] == '\xfe') || (text[0] == '\xfe' && text[1] == '\xff'));
  if (bom16 || text.find('\0') != std::string::npos) {
    return "is not a text file in ASCII or UTF-8 (UTF-16, or binary); save it as UTF-8";
  }
  return "";
}

// The OBJ's triangles (and, when materials are wanted, its mtllib's
// materials, whose file's path goes to `mtlPath`); a missing mtllib is a
// warning.
ObjTriangles parseObj(FileSource& files, const std::string& path, const std::string& place,
                      const LoadLimits& limits, bool withMaterials, std::vector<std::string>& warnings,
                      std::string& mtlPath) {
  const std::string& text = files.read(path, place);
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
  return parseObjTriangles(text, mtl, limits, place + ": '" + path + "'");
}

// The materials of the MTL file at `mtlPath`, each map_Kd (relative to the
// MTL file) decoded as the material's texture; a missing texture is a
// warning, and the material keeps its Kd colour.
void readMaterials(const std::vector<tinyobj::material_t>& materials, FileSource& files, const std::string& mtlPath,
                   const std::string& place, ImageCache& images, MeshModel& model) {
  for (const tinyobj::material_t& m : materials) {
    Material mat = toMaterial(m);
    const std::string texPath = m.diffuse_texname.empty() ? "" : siblingPath(mtlPath, m.diffuse_texname);
    if (!texPath.empty() && !files.has(texPath)) {
      model.warnings.push_back("'" + mtlPath + "' names the texture '" + texPath + "' (map_Kd of material " +
                               m.name + "), which is missing; the material's Kd colour is used");
    } else if (!texPath.empty()) {
      const std::string texPlace = place + " (map_Kd of material " + m.name + ", " + texPath + ")";
      Texture tex;
      tex.type = TextureType::kImage;
      tex.image = images.get(texPath, texPlace);
      mat.texture = static_cast<int>(model.textures.size());
      mat.color = glm::vec3(1.0f);
      model.textures.push_back(std::move(tex));
    }
    model.materials.push_back(std::move(mat));
  }
}

// The faces of one material become one mesh; a corner (position, normal, uv)
// seen before in that material reuses its vertex, so vertices come in the
// order their first corners do. Most positions are only ever used one way
// (one material, one normal, one uv): the first use of each position is
// kept in an array indexed by it, and only other uses go to a hash map
// (the ordered map this replaced took two thirds of a large OBJ's load).
class FaceGrouper {
 public:
  // Room for the meshes of `triangles` (the file's triangles by material),
  // faulted in at once: a mesh gets its corners' indices and (a guess) its
  // share of the file's vertices.
  FaceGrouper(const tinyobj::attrib_t& attrib, const std::map<int, std::size_t>& triangles)
      : attrib_(attrib),
        normals_(!attrib.normals.empty()),
        uvs_(!attrib.texcoords.empty()),
        colors_(!attrib.colors.empty() && attrib.colors.size() == attrib.vertices.size()) {
    const std::size_t positions = attrib.vertices.size() / 3;
    reservePrefaulted(first_, positions);
    first_.resize(positions);
    std::size_t all = 0;
    for (const auto& [material, count] : triangles) all += count;
    for (const auto& [material, count] : triangles) {
      MeshInput& mesh = groups_[material].mesh;
      const std::size_t vertices = std::min(3 * count, positions * count / std::max<std::size_t>(all, 1) + 1);
      reservePrefaulted(mesh.indices, 3 * count);
      reservePrefaulted(mesh.positions, vertices);
      if (normals_) reservePrefaulted(mesh.normals, vertices);
      if (uvs_) reservePrefaulted(mesh.uvs, vertices);
      if (colors_) reservePrefaulted(mesh.colors, vertices);
    }
  }

  // A corner whose indices name the file's data (ObjTriangles checked them).
  void addCorner(int material, const tinyobj::index_t& idx) {
    Group& group = groupOf(material);
    const auto next = static_cast<std::uint32_t>(group.mesh.positions.size());
    FirstUse& first = first_[static_cast<std::size_t>(idx.vertex_index)];
    std::uint32_t index = next;
    if (first.material == kUnused) {
      first = {material, idx.normal_index, idx.texcoord_index, next};
    } else if (first.material == material && first.normal == idx.normal_index && first.uv == idx.texcoord_index) {
      index = first.index;
    } else {
      index = others_.try_emplace({material, idx.vertex_index, idx.normal_index, idx.texcoord_index}, next).first->second;
    }
    if (index == next) addVertex(group, idx);
    group.mesh.indices.push_back(index);
  }

  // The meshes; a mesh some of whose corners lack a normal gets its normals
  // from the faces instead.
  void finish(MeshModel& model) {
    for (auto& [mat, group] : groups_) {
      if (!group.complete) group.mesh.normals.clear();
      group.mesh.material = static_cast<std::uint32_t>(mat);
      model.meshes.push_back(std::move(group.mesh));
    }
  }
  bool uses(int material) const { return groups_.count(material) > 0; }

 private:
  static constexpr int kUnused = -2;  // materials are >= 0
  struct FirstUse {
    int material = kUnused;
    int normal = 0;
    int uv = 0;
    std::uint32_t index = 0;
  };
  struct Group {
    MeshInput mesh;
    bool complete = true;  // every corner has a normal
  };

  Group& groupOf(int material) {
    if (material != lastMaterial_ || !last_) {
      last_ = &groups_[material];
      lastMaterial_ = material;
    }
    return *last_;
  }

  void addVertex(Group& group, const tinyobj::index_t& idx) {
    MeshInput& mesh = group.mesh;
    const auto v = static_cast<std::size_t>(idx.vertex_index);
    mesh.positions.emplace_back(attrib_.vertices[3 * v], attrib_.vertices[3 * v + 1], attrib_.vertices[3 * v + 2]);
    if (colors_) mesh.colors.emplace_back(attrib_.colors[3 * v], attrib_.colors[3 * v + 1], attrib_.colors[3 * v + 2]);
    group.complete = group.complete && idx.normal_index >= 0;
    if (normals_) {  // a file without normals gives meshes without (so do files with too few: finish())
      const auto n = static_cast<std::size_t>(std::max(idx.normal_index, 0));
      mesh.normals.push_back(idx.normal_index >= 0 ? glm::vec3(attrib_.normals[3 * n], attrib_.normals[3 * n + 1],
                                                               attrib_.normals[3 * n + 2])
                                                   : glm::vec3(0.0f));
    }
    if (uvs_) {  // and one without uvs, meshes without (uv (0, 0) everywhere, as absent uvs give)
      const auto t = static_cast<std::size_t>(std::max(idx.texcoord_index, 0));
      mesh.uvs.push_back(idx.texcoord_index >= 0 ? glm::vec2(attrib_.texcoords[2 * t], attrib_.texcoords[2 * t + 1])
                                                 : glm::vec2(0.0f));
    }
  }

  const tinyobj::attrib_t& attrib_;
  const bool normals_;  // the file has normals
  const bool uvs_;      // the file has uvs
  const bool colors_;   // the file has vertex colours, one a position
  std::vector<FirstUse> first_;  // by position index
  std::unordered_map<std::array<int, 4>, std::uint32_t, ArrayHash> others_;  // (material, v, n, t) -> vertex
  std::map<int, Group> groups_;  // by material; its nodes stay put, so last_ stays valid
  Group* last_ = nullptr;
  int lastMaterial_ = kUnused;
};

}  // namespace

MeshModel loadObj(FileSource& files, const std::string& path, const std::string& place, SceneBudget& budget,
                 bool withMaterials, ImageCache* images) {
  const LoadLimits& limits = budget.limits();
  MeshModel model;
  std::string mtlPath;
  const ObjTriangles obj = parseObj(files, path, place, limits, withMaterials, model.warnings, mtlPath);
  if (!mtlPath.empty()) {
    ImageCache own(files, budget);
    readMaterials(obj.materials, files, mtlPath, place, images ? *images : own, model);
  }
  // Faces without a material (or all faces, without MTL) use a default one.
  const int defaultMaterial = static_cast<int>(model.materials.size());
  const auto materialOf = [&](std::size_t t) {
    return obj.materialOf[t] >= 0 && obj.materialOf[t] < defaultMaterial ? obj.materialOf[t] : defaultMaterial;
  };
  std::map<int, std::size_t> triangles;  // by material
  for (std::size_t t = 0; t < obj.materialOf.size(); ++t) ++triangles[materialOf(t)];
  FaceGrouper grouper(obj.attrib, triangles);
  for (std::size_t t = 0; t < obj.materialOf.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) grouper.addCorner(materialOf(t), obj.corners[3 * t + k]);
  }
  if (obj.materialOf.empty()) {
    throw InputError(place + ": '" + path + "' holds no triangle (" + std::to_string(obj.attrib.vertices.size() / 3) +
                     " vertices, no faces: points or lines only?); a mesh needs faces (f lines)");
  }
  grouper.finish(model);
  if (grouper.uses(defaultMaterial)) model.materials.push_back(Material{});
  return model;
}

}  // namespace glint
