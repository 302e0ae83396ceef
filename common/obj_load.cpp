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

// MTL -> Glint: Kd is the surface colour C (or map_Kd the texture) with r_D
// = 1, so that C r_D = Kd; r_A and r_S are the means of Ka and Ks; Ns is h;
// Ni the index; d (or 1 - Tr) the opacity.
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
  return out;
}

struct VertexKey {
  int v, n, t;
  auto operator<=>(const VertexKey&) const = default;
};

}  // namespace

ObjModel loadObj(FileSource& files, const std::string& path, const std::string& place,
                 SceneBudget& budget, bool withMaterials) {
  const LoadLimits& limits = budget.limits();
  const std::string text = files.read(path, place);
  std::string mtl;
  const std::string lib = mtllibName(text);
  if (withMaterials && !lib.empty()) mtl = files.read(siblingPath(path, lib), place + " (mtllib " + lib + ")");

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, mtl, config)) {
    throw InputError(place + ": '" + path + "' is not a valid OBJ file: " + reader.Error());
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const std::size_t positions = attrib.vertices.size() / 3;
  const std::size_t normals = attrib.normals.size() / 3;
  const std::size_t uvs = attrib.texcoords.size() / 2;
  if (positions > limits.maxVertices) {
    throw InputError(place + ": '" + path + "' has " + std::to_string(positions) +
                     " vertices, over the limit of " + std::to_string(limits.maxVertices));
  }

  ObjModel model;
  if (withMaterials) {
    for (const tinyobj::material_t& m : reader.GetMaterials()) {
      Material mat = toMaterial(m);
      if (!m.diffuse_texname.empty()) {
        const std::string texPath = siblingPath(path, m.diffuse_texname);
        const std::string texPlace = place + " (map_Kd of material " + m.name + ")";
        Texture tex;
        tex.type = TextureType::kImage;
        tex.image = std::make_shared<Image>(
            decodeImage(files.read(texPath, texPlace), texPlace, budget));
        mat.texture = static_cast<int>(model.textures.size());
        mat.color = glm::vec3(1.0f);
        model.textures.push_back(std::move(tex));
      }
      model.materials.push_back(std::move(mat));
    }
  }
  // Faces without a material (or all faces, without MTL) use a default one.
  const int defaultMaterial = static_cast<int>(model.materials.size());

  std::map<int, MeshInput> groups;
  std::map<int, std::map<VertexKey, std::uint32_t>> vertexMaps;
  std::map<int, bool> complete;  // every corner has a normal / uv
  std::size_t triangles = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& mesh = shape.mesh;
    for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      if (mesh.num_face_vertices[f] != 3) {
        throw InputError(place + ": '" + path + "' face " + std::to_string(f) + " of '" + shape.name +
                         "' could not be triangulated");
      }
      if (++triangles > limits.maxTriangles) {
        throw InputError(place + ": '" + path + "' has more triangles than the limit of " +
                         std::to_string(limits.maxTriangles));
      }
      int mat = withMaterials && f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      if (mat < 0 || mat >= defaultMaterial) mat = defaultMaterial;
      MeshInput& group = groups[mat];
      auto& vertexMap = vertexMaps[mat];
      for (int k = 0; k < 3; ++k) {
        const tinyobj::index_t& idx = mesh.indices[3 * f + static_cast<std::size_t>(k)];
        if (idx.vertex_index < 0 || static_cast<std::size_t>(idx.vertex_index) >= positions ||
            idx.normal_index >= static_cast<int>(normals) || idx.texcoord_index >= static_cast<int>(uvs)) {
          throw InputError(place + ": '" + path + "' face " + std::to_string(f) + " of '" + shape.name +
                           "' refers to a vertex, normal or uv that the file does not have");
        }
        const VertexKey key{idx.vertex_index, idx.normal_index, idx.texcoord_index};
        auto [it, inserted] = vertexMap.try_emplace(key, static_cast<std::uint32_t>(group.positions.size()));
        if (inserted) {
          const auto v = static_cast<std::size_t>(idx.vertex_index);
          group.positions.emplace_back(attrib.vertices[3 * v], attrib.vertices[3 * v + 1],
                                       attrib.vertices[3 * v + 2]);
          const auto n = static_cast<std::size_t>(std::max(idx.normal_index, 0));
          group.normals.push_back(idx.normal_index >= 0
                                      ? glm::vec3(attrib.normals[3 * n], attrib.normals[3 * n + 1],
                                                  attrib.normals[3 * n + 2])
                                      : glm::vec3(0.0f));
          const auto t = static_cast<std::size_t>(std::max(idx.texcoord_index, 0));
          group.uvs.push_back(idx.texcoord_index >= 0
                                  ? glm::vec2(attrib.texcoords[2 * t], attrib.texcoords[2 * t + 1])
                                  : glm::vec2(0.0f));
          auto [c, fresh] = complete.try_emplace(mat, true);
          c->second = c->second && idx.normal_index >= 0;
        }
        group.indices.push_back(it->second);
      }
    }
  }
  for (auto& [mat, group] : groups) {
    if (!complete[mat]) group.normals.clear();  // computed from the faces instead
    group.material = static_cast<std::uint32_t>(mat);
    model.meshes.push_back(std::move(group));
  }
  if (groups.count(defaultMaterial)) model.materials.push_back(Material{});
  return model;
}

}  // namespace glint
