#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace glint {

// What a glTF 2.0 file (.gltf JSON, or the JSON chunk of a .glb) asks for
// that Glint does not apply. An extension its meshes cannot be read
// without (KHR_draco_mesh_compression, which Assimp renders as garbage) is
// an InputError starting with `place` and naming it; the other extensions
// the file uses (clearcoat, lights ...) are returned,
// "KHR_a, KHR_b", for a warning, so that nothing is dropped silently ("" for
// none). InputError when the JSON cannot be read.
std::string unappliedGltfExtensions(std::string_view bytes, const std::string& place);

}  // namespace glint
