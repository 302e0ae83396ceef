#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace glint {

// The JSON of a glTF 2.0 file: a .gltf's text, or a .glb's first chunk.
// InputError, starting with `place`, when it is not glTF JSON.
nlohmann::json gltfJson(std::string_view bytes, const std::string& place);

}  // namespace glint
