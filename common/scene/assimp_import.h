#pragma once

#include <string>
#include <string_view>

#include "common/base/file_source.h"
#include "common/scene/mesh_model.h"
#include "common/scene/scene_budget.h"

namespace glint {

// Reads a glTF 2.0 (.gltf with its buffers and images, or .glb) or PLY file
// with the Open Asset Import Library: the file at `path` from `bytes` (read
// already), the files it names through `files` (readForImport): node transforms applied, polygons triangulated, points
// and lines left out. Materials: base colour (or diffuse) and its texture,
// opacity as transparency, and for glTF metallic x (1 - roughness) as the
// reflectivity, its roughness the reflection's. A missing texture is a warning; a file that yields no
// triangle is an error. Errors start with `place`.
MeshModel importWithAssimp(FileSource& files, const std::string& path, std::string_view bytes,
                           const std::string& place, SceneBudget& budget);

}  // namespace glint
