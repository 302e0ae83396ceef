#pragma once

#include <string>
#include <vector>

#include "common/file_source.h"
#include "common/geometry.h"
#include "common/scene_budget.h"
#include "common/material.h"
#include "common/texture.h"

namespace glint {

// A Wavefront OBJ file as triangle meshes, one per MTL material it uses.
// MeshInput::material indexes `materials` (the file's MTL materials, mapped
// onto Glint's fields); `textures` are the materials' map_Kd images, and
// Material::texture indexes them.
struct ObjModel {
  std::vector<MeshInput> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<std::string> warnings;  // files the OBJ names that are missing
};

// Parses the OBJ at `path` (read through `files`) with tinyobjloader. With
// withMaterials, its mtllib is read too; otherwise every face goes into one
// mesh with material 0. A missing MTL file or texture is a warning (the
// default material, the Kd colour); a file that yields no triangle (empty,
// UTF-16, points or lines only) is an error. Errors start with `place`.
ObjModel loadObj(FileSource& files, const std::string& path, const std::string& place,
                 SceneBudget& budget, bool withMaterials);

}  // namespace glint
