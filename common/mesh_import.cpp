#include "common/mesh_import.h"

#include <algorithm>
#include <filesystem>

#include "common/assimp_import.h"
#include "common/error.h"
#include "common/mesh_blob.h"
#include "common/obj_load.h"

namespace glint {

MeshModel importMeshFile(FileSource& files, const std::string& path, const std::string& place, SceneBudget& budget,
                         bool withMaterials) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  const std::optional<MeshFormat> format = enumFromWord<MeshFormat>(extension);
  if (!format) {
    throw InputError(place + ": '" + path + "': mesh files are " + enumWordsJoined<MeshFormat>() +
                     " (Wavefront OBJ, PLY, glTF 2.0)");
  }
  if (*format == MeshFormat::kObj) return loadObj(files, path, place, budget, withMaterials);
  if (!files.importsMeshes()) return decodeMeshBlob(files.read(path, place), place, budget);
  MeshModel model = importWithAssimp(files, path, place, budget, withMaterials);
  files.keepImported(path, encodeMeshBlob(model));
  return model;
}

}  // namespace glint
