#include "common/scene/gltf_extensions.h"

#include "common/base/error.h"
#include "common/scene/gltf_json.h"

namespace glint {
namespace {

// Extensions whose meshes Assimp cannot decode: an error, not a warning.
constexpr std::string_view kUnreadable[] = {"KHR_draco_mesh_compression", "EXT_meshopt_compression"};

// Extensions Glint applies (common/scene/gltf_texture_transform.h, and
// gltf_lights.h where the scene's mesh asks for the file's lights).
constexpr std::string_view kApplied[] = {"KHR_texture_transform", "KHR_lights_punctual"};

template <std::size_t N>
bool listed(const std::string& name, const std::string_view (&list)[N]) {
  for (const std::string_view u : list) {
    if (name == u) return true;
  }
  return false;
}

}  // namespace

std::string unappliedGltfExtensions(std::string_view bytes, const std::string& place) {
  const nlohmann::json doc = gltfJson(bytes, place);
  std::string used;
  for (const char* key : {"extensionsRequired", "extensionsUsed"}) {
    const nlohmann::json list = doc.value(key, nlohmann::json::array());
    if (!list.is_array()) continue;
    for (const nlohmann::json& name : list) {
      if (!name.is_string()) continue;
      const std::string extension = name.get<std::string>();
      if (listed(extension, kUnreadable)) {
        throw InputError(place + ": uses " + extension +
                         ", compressed meshes Glint cannot read; export the model without mesh compression");
      }
      if (listed(extension, kApplied)) continue;
      if (used.find(extension) == std::string::npos) used += (used.empty() ? "" : ", ") + extension;
    }
  }
  return used;
}

}  // namespace glint
