#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "common/scene/camera.h"

namespace glint {

// The first perspective camera of a glTF 2.0 file (.gltf JSON, or the JSON
// chunk of a .glb), placed by its node and the node's parents (matrix, or
// translation x rotation x scale): the eye at the node's origin, looking
// down its -Z with +Y up, fov_y its yfov in degrees. None when the file has
// no perspective camera; InputError (starting with `place`) when the JSON
// cannot be read. Read here rather than through Assimp, whose glTF cameras
// mix the node's translation into the camera and give a horizontal angle.
std::optional<CameraSpec> gltfCamera(std::string_view bytes, const std::string& place);

}  // namespace glint
