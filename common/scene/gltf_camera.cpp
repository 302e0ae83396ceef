#include "common/scene/gltf_camera.h"

#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "common/base/error.h"
#include "common/scene/gltf_json.h"
#include "common/scene/gltf_nodes.h"

namespace glint {
using nlohmann::json;

std::optional<CameraSpec> gltfCamera(std::string_view bytes, const std::string& place) {
  const json doc = gltfJson(bytes, place);
  const json nodes = doc.value("nodes", json::array()), cameras = doc.value("cameras", json::array());
  const std::vector<glm::mat4> worlds = gltfNodeWorlds(doc);
  for (std::size_t i = 0; i < worlds.size(); ++i) {
    const json& node = nodes[i];
    if (!node.is_object() || !node.contains("camera") || !node["camera"].is_number_unsigned()) continue;
    const std::size_t c = node["camera"].get<std::size_t>();
    if (c >= cameras.size() || cameras[c].value("type", "") != "perspective") continue;
    const glm::mat4& world = worlds[i];
    CameraSpec spec;
    spec.eye = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    spec.lookAt = spec.eye + glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
    spec.up = glm::normalize(glm::vec3(world * glm::vec4(0, 1, 0, 0)));
    spec.fovY = glm::degrees(cameras[c].value("perspective", json::object()).value("yfov", glm::radians(45.0f)));
    return spec;
  }
  return std::nullopt;
}

}  // namespace glint
