#pragma once

#include <filesystem>
#include <string>

#include "common/base/file_source.h"

namespace glint {

// The text of the scene a command opens for `path`: a scene file's own
// JSON, or, for a model file (.gltf, .glb, .obj, .ply, any case), the
// default scene around it (docs/scene-format.md, "A model file on its
// own"): the model by its name in its folder, its own first camera and
// KHR_lights_punctual lights when it has them, else a camera fitted to it
// and a three-light rig. `folder` reads from the file's folder. A file that
// is neither (not .json, and not JSON) is an InputError saying what Glint
// reads.
std::string sceneTextFor(const std::filesystem::path& path, FileSource& folder);

}  // namespace glint
