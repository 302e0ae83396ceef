#pragma once

#include <string>

#include "common/base/enum_words.h"
#include "common/base/file_source.h"
#include "common/scene/image_cache.h"
#include "common/scene/mesh_model.h"
#include "common/scene/scene_budget.h"

namespace glint {

// The mesh file formats a scene's "mesh" reads, by extension.
enum class MeshFormat { kObj, kPly, kGltf, kGlb };

template <>
struct EnumWords<MeshFormat> {
  static constexpr std::array<std::pair<MeshFormat, std::string_view>, 4> kWords{
      {{MeshFormat::kObj, ".obj"}, {MeshFormat::kPly, ".ply"}, {MeshFormat::kGltf, ".gltf"}, {MeshFormat::kGlb, ".glb"}}};
};

// A mesh file of any of those formats. OBJ is read by tinyobjloader
// (common/scene/obj_load.h) everywhere. glTF and PLY are imported by Assimp
// (common/scene/assimp_import.h) where the source reads the disk, and the imported
// mesh is kept as a blob (common/scene/mesh_blob.h) for the scene's bundle; a
// source in memory (a server) reads that blob instead. Errors start with
// `place`. An OBJ's textures come through `images` where given.
MeshModel importMeshFile(FileSource& files, const std::string& path, const std::string& place, SceneBudget& budget,
                         bool withMaterials, ImageCache* images = nullptr);

}  // namespace glint
