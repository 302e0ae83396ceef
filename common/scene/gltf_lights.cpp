#include "common/scene/gltf_lights.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>
#include <nlohmann/json.hpp>

#include "common/base/error.h"
#include "common/math/circular.h"
#include "common/math/finite.h"
#include "common/scene/gltf_json.h"
#include "common/scene/gltf_nodes.h"

namespace glint {
namespace {

using nlohmann::json;

constexpr float kDefaultOuterCone = 0.78539816f;  // pi / 4, glTF's default

// j[key], or null where j is not an object or lacks it.
const json& member(const json& j, const char* key) {
  static const json kNone;
  if (!j.is_object()) return kNone;
  const auto it = j.find(key);
  return it == j.end() ? kNone : *it;
}

// A number as the renderer holds it: a float (a double beyond float's
// range would become infinite).
float finite(const json& value, float fallback, const std::string& what) {
  if (value.is_null()) return fallback;
  if (!value.is_number() || !std::isfinite(value.get<double>())) throw InputError(what + " is not a number");
  if (std::abs(value.get<double>()) > std::numeric_limits<float>::max()) {
    throw InputError(what + " is beyond a float's range (3.4e38)");
  }
  return static_cast<float>(value.get<double>());
}

// The light of entry `light` as placed by `world`.
Light fromEntry(const json& entry, const glm::mat4& world, const std::string& place) {
  if (!entry.is_object()) throw InputError(place + ": not an object");
  Light light;
  const json& type = member(entry, "type");
  const json& color = member(entry, "color");
  if (!color.is_null() && (!color.is_array() || color.size() != 3)) {
    throw InputError(place + ": color is not three numbers");
  }
  const float intensity = finite(member(entry, "intensity"), 1.0f, place + ": intensity");
  for (std::size_t k = 0; k < 3; ++k) {
    light.color[static_cast<int>(k)] = (color.is_null() ? 1.0f : finite(color[k], 1.0f, place + ": color")) * intensity;
  }
  if (!(intensity >= 0.0f) || glm::any(glm::lessThan(light.color, glm::vec3(0.0f)))) {
    throw InputError(place + ": its color and intensity must not be negative");
  }
  if (!allFinite(light.color)) throw InputError(place + ": its color times its intensity is beyond a float's range");
  light.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
  const glm::vec3 axis(world * glm::vec4(0, 0, -1, 0));
  if (!allFinite(light.position) || !allFinite(axis)) {
    throw InputError(place + ": its node's transform is beyond a float's range");
  }
  if (!(glm::length(axis) > 0.0f)) throw InputError(place + ": its node's transform has no direction");
  light.direction = glm::vec3(glm::normalize(glm::dvec3(axis)));  // in double: the axis may be 1e38 long
  light.attenuation = {0.0f, 0.0f, 1.0f};
  if (type == "point") {
    light.type = LightType::kPoint;
  } else if (type == "spot") {
    light.type = LightType::kSpot;
    const json& spot = member(entry, "spot");
    const float inner = finite(member(spot, "innerConeAngle"), 0.0f, place + ": innerConeAngle");
    const float outer = finite(member(spot, "outerConeAngle"), kDefaultOuterCone, place + ": outerConeAngle");
    if (!(inner >= 0.0f && inner <= outer && outer <= 1.5707964f)) {
      throw InputError(place + ": spot cones must satisfy 0 <= innerConeAngle <= outerConeAngle <= pi / 2");
    }
    light.cosInner = sineCosine(inner).cos;
    light.cosOuter = sineCosine(outer).cos;
  } else if (type == "directional") {
    light.type = LightType::kDirectional;
    light.attenuation = {1.0f, 0.0f, 0.0f};
  } else {
    throw InputError(place + ": its type is not point, spot or directional");
  }
  return light;
}

}  // namespace

std::vector<Light> gltfLights(std::string_view bytes, const std::string& place) {
  const json doc = gltfJson(bytes, place);
  const json& lights = member(member(member(doc, "extensions"), "KHR_lights_punctual"), "lights");
  if (!lights.is_array() || lights.empty()) return {};
  const json& nodes = member(doc, "nodes");
  const std::vector<glm::mat4> worlds = gltfNodeWorlds(doc);
  std::vector<Light> out;
  for (std::size_t i = 0; i < worlds.size(); ++i) {
    const json& ref = member(member(nodes[i], "extensions"), "KHR_lights_punctual");
    if (ref.is_null()) continue;
    const std::string where = place + ": node " + std::to_string(i) + "'s KHR_lights_punctual light";
    const json& index = member(ref, "light");
    if (!index.is_number_unsigned() || index.get<std::size_t>() >= lights.size()) {
      throw InputError(where + " names no light of the file");
    }
    out.push_back(fromEntry(lights[index.get<std::size_t>()], worlds[i], where));
  }
  return out;
}

}  // namespace glint
