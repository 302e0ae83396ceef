#include "common/scene/gltf_nodes.h"

#include <map>

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace glint {
namespace {

using nlohmann::json;

float number(const json& j, std::size_t i, float fallback) {
  return j.is_array() && i < j.size() && j[i].is_number() ? j[i].get<float>() : fallback;
}

glm::mat4 localTransform(const json& node) {
  if (!node.is_object()) return glm::mat4(1.0f);
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

std::vector<glm::mat4> gltfNodeWorlds(const json& doc) {
  const json nodes = doc.value("nodes", json::array());
  if (!nodes.is_array()) return {};
  std::map<std::size_t, std::size_t> parent;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!nodes[i].is_object()) continue;
    for (const json& c : nodes[i].value("children", json::array())) {
      if (c.is_number_unsigned()) parent.emplace(c.get<std::size_t>(), i);
    }
  }
  std::vector<glm::mat4> worlds;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    glm::mat4 world = localTransform(nodes[i]);
    std::size_t depth = 0;
    for (auto p = parent.find(i); p != parent.end() && depth++ < nodes.size(); p = parent.find(p->second)) {
      world = localTransform(nodes[p->second]) * world;
    }
    worlds.push_back(world);
  }
  return worlds;
}

}  // namespace glint
