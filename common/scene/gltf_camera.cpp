#include "common/scene/gltf_camera.h"

#include <cstdint>
#include <cstring>
#include <map>

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "common/base/error.h"
#include "common/scene/gltf_json.h"

namespace glint {
namespace {

using nlohmann::json;

float number(const json& j, std::size_t i, float fallback) {
  return j.is_array() && i < j.size() && j[i].is_number() ? j[i].get<float>() : fallback;
}

// A node's own transform (glTF 2.0, 5.25: matrix, or T * R * S).
glm::mat4 localTransform(const json& node) {
  if (const auto m = node.find("matrix"); m != node.end() && m->is_array() && m->size() == 16) {
    glm::mat4 out;
    for (int i = 0; i < 16; ++i) glm::value_ptr(out)[i] = number(*m, static_cast<std::size_t>(i), 0.0f);  // column-major
    return out;
  }
  const json t = node.value("translation", json::array()), r = node.value("rotation", json::array()),
             s = node.value("scale", json::array());
  const glm::quat q(number(r, 3, 1.0f), number(r, 0, 0.0f), number(r, 1, 0.0f), number(r, 2, 0.0f));
  return glm::translate(glm::mat4(1.0f), {number(t, 0, 0.0f), number(t, 1, 0.0f), number(t, 2, 0.0f)}) *
         glm::mat4_cast(q) * glm::scale(glm::mat4(1.0f), {number(s, 0, 1.0f), number(s, 1, 1.0f), number(s, 2, 1.0f)});
}

}  // namespace

std::optional<CameraSpec> gltfCamera(std::string_view bytes, const std::string& place) {
  const json doc = gltfJson(bytes, place);
  const json nodes = doc.value("nodes", json::array()), cameras = doc.value("cameras", json::array());
  std::map<std::size_t, std::size_t> parent;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (const json& c : nodes[i].value("children", json::array())) {
      if (c.is_number_unsigned()) parent.emplace(c.get<std::size_t>(), i);
    }
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const json& node = nodes[i];
    if (!node.is_object() || !node.contains("camera") || !node["camera"].is_number_unsigned()) continue;
    const std::size_t c = node["camera"].get<std::size_t>();
    if (c >= cameras.size() || cameras[c].value("type", "") != "perspective") continue;
    glm::mat4 world = localTransform(node);
    std::size_t depth = 0;  // a cycle of parents is not glTF; stop at the node count
    for (auto p = parent.find(i); p != parent.end() && depth++ < nodes.size(); p = parent.find(p->second)) {
      world = localTransform(nodes[p->second]) * world;
    }
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
