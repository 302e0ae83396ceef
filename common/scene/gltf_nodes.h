#pragma once

#include <vector>

#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

namespace glint {

// Each node of a glTF 2.0 document placed in the world: its own transform
// (matrix, or translation x rotation x scale; glTF 2.0, 5.25) after its
// parents'. A malformed entry counts as the identity; a cycle of parents (not
// glTF) stops at the node count. Empty when `nodes` is not an array.
std::vector<glm::mat4> gltfNodeWorlds(const nlohmann::json& doc);

}  // namespace glint
