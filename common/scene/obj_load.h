#pragma once

#include <string>

#include "common/base/file_source.h"
#include "common/scene/image_cache.h"
#include "common/scene/mesh_model.h"
#include "common/scene/scene_budget.h"

namespace glint {

// Parses the OBJ at `path` (read through `files`) with tinyobjloader. With
// withMaterials, its mtllib is read too; otherwise every face goes into one
// mesh with material 0. A missing MTL file or texture is a warning (the
// default material, the Kd colour); a file that yields no triangle (empty,
// UTF-16, points or lines only) is an error. Errors start with `place`.
// Textures come through `images` (a scene's load shares one), or through a
// cache of this file's own.
MeshModel loadObj(FileSource& files, const std::string& path, const std::string& place, SceneBudget& budget,
                  bool withMaterials, ImageCache* images = nullptr);

}  // namespace glint
