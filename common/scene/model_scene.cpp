#include "common/scene/model_scene.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <string_view>

#include <nlohmann/json.hpp>

#include "common/base/error.h"
#include "common/scene/gltf_json.h"

namespace glint {
namespace {

using json = nlohmann::json;

constexpr std::array<std::string_view, 4> kModelExtensions = {".gltf", ".glb", ".obj", ".ply"};

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool isModel(const std::string& ext) {
  return std::find(kModelExtensions.begin(), kModelExtensions.end(), ext) != kModelExtensions.end();
}

// What a glTF file brings of its own: a perspective camera, punctual lights.
struct Authored {
  bool camera = false;
  float aspect = 4.0f / 3.0f;  // the camera's aspectRatio when it gives one: the image's width / height
  bool lights = false;
};

Authored authoredIn(const json& doc) {
  Authored a;
  for (const json& c : doc.value("cameras", json::array())) {
    if (a.camera || !c.is_object() || c.value("type", "") != "perspective") continue;
    a.camera = true;  // the first perspective camera, as "camera": {"file": ...} takes
    const json p = c.value("perspective", json::object());
    const json ratio = p.is_object() ? p.value("aspectRatio", json()) : json();
    if (ratio.is_number() && ratio.get<double>() >= 0.25 && ratio.get<double>() <= 4.0) a.aspect = ratio.get<float>();
  }
  const json lights = doc.value("extensions", json::object()).value("KHR_lights_punctual", json::object());
  a.lights = !lights.value("lights", json::array()).empty();
  return a;
}

// A file whose cameras or lights are malformed gets the default camera and
// rig here; the loader then names what is wrong with it, if it reads them.
Authored authoredIn(const std::string& bytes, const std::string& place) {
  const json doc = gltfJson(bytes, place);
  try {
    return authoredIn(doc);
  } catch (const json::exception&) {
    return {};
  }
}

// A key light from the upper left front, a dimmer fill from the right and
// a rim light from behind: each side of the model shows its shape.
json lightRig() {
  const auto directional = [](std::array<float, 3> direction, float power) {
    return json{{"type", "directional"}, {"direction", direction}, {"color", {power, power, power}}};
  };
  return json::array({directional({0.6f, -1.0f, -0.8f}, 0.9f), directional({-1.0f, -0.3f, -0.4f}, 0.3f),
                      directional({0.2f, -0.5f, 1.0f}, 0.4f)});
}

std::string modelScene(const std::string& name, const Authored& authored) {
  json mesh{{"type", "mesh"}, {"file", name}};
  constexpr int kHeight = 480;
  const int width = static_cast<int>(std::lround(kHeight * authored.aspect));
  json scene{{"glint", 1}, {"image", {{"width", width}, {"height", kHeight}}}, {"background", {0.1, 0.1, 0.12}}};
  if (authored.camera) {
    scene["camera"] = {{"file", name}};
  } else {
    scene["camera"] = {{"eye", {1.6, 1.0, 2.4}}, {"look_at", {0, 0, 0}}, {"fov_y", 40}, {"fit", true}};
  }
  if (authored.lights) {
    mesh["lights"] = true;
  } else {
    scene["lights"] = lightRig();
  }
  scene["objects"] = json::array({mesh});
  return scene.dump();
}

}  // namespace

std::string sceneTextFor(const std::filesystem::path& path, FileSource& folder) {
  const std::string name = path.filename().string();
  const std::string ext = lowerExtension(path);
  if (isModel(ext)) {
    if (ext == ".gltf" || ext == ".glb") return modelScene(name, authoredIn(folder.read(name, "model file"), name));
    if (!folder.has(name)) folder.read(name, "model file");  // throws: a missing file is named as one
    return modelScene(name, Authored{});
  }
  const std::string& text = folder.read(name, "scene file");
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (ext != ".json" && (first == std::string::npos || text[first] != '{')) {
    throw InputError("neither a Glint scene (JSON, docs/scene-format.md) nor a model file Glint opens (.gltf, .glb, "
                     ".obj, .ply)");
  }
  return text;
}

}  // namespace glint
