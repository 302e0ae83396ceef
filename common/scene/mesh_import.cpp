#include "common/scene/mesh_import.h"

#include <algorithm>
#include <filesystem>

#include "common/scene/assimp_import.h"
#include "common/base/error.h"
#include "common/scene/gltf_camera.h"
#include "common/scene/gltf_lights.h"
#include "common/scene/gltf_extensions.h"
#include "common/scene/mesh_blob.h"
#include "common/scene/obj_load.h"

namespace glint {

MeshModel importMeshFile(FileSource& files, const std::string& path, const std::string& place, SceneBudget& budget,
                         bool withMaterials, ImageCache* images) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  const std::optional<MeshFormat> format = enumFromWord<MeshFormat>(extension);
  if (!format) {
    throw InputError(place + ": '" + path + "': mesh files are " + enumWordsJoined<MeshFormat>() +
                     " (Wavefront OBJ, PLY, glTF 2.0)");
  }
  if (*format == MeshFormat::kObj) return loadObj(files, path, place, budget, withMaterials, images);
  MeshModel model;
  if (!files.importsMeshes()) {
    model = decodeMeshBlob(files.read(path, place), place, budget);
  } else {
    const std::string bytes = files.readForImport(path, place);  // once, for Assimp and the camera
    const bool gltf = *format == MeshFormat::kGltf || *format == MeshFormat::kGlb;
    const std::string extensions = gltf ? unappliedGltfExtensions(bytes, place + ": '" + path + "'") : "";
    model = importWithAssimp(files, path, bytes, place, budget);
    if (!extensions.empty()) {
      model.warnings.push_back("'" + path + "' uses glTF extensions Glint does not apply (" + extensions +
                               "): rendered without them");
    }
    if (gltf) {
      model.camera = gltfCamera(bytes, place + ": '" + path + "'");
      model.lights = gltfLights(bytes, place + ": '" + path + "'");
    }
    checkImportedModel(model, place + ": '" + path + "'");  // as decodeMeshBlob does on a server
    files.keepImported(path, encodeMeshBlob(model));  // always with its materials, whoever asks next
  }
  if (!withMaterials) {
    for (MeshInput& mesh : model.meshes) mesh.material = 0;
    model.materials.assign(1, Material{});
    model.textures.clear();
  }
  return model;
}

}  // namespace glint
