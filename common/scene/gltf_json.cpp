#include "common/scene/gltf_json.h"

#include <cstdint>
#include <cstring>

#include "common/base/error.h"

namespace glint {
namespace {

constexpr std::uint32_t kJsonChunk = 0x4E4F534Au;  // "JSON", little-endian
constexpr std::size_t kGlbHeaderBytes = 20;         // file header (12) and the first chunk's (8)

std::string_view jsonText(std::string_view bytes, const std::string& place) {
  if (bytes.substr(0, 4) != "glTF") return bytes;
  std::uint32_t length = 0, type = 0;
  if (bytes.size() < kGlbHeaderBytes) throw InputError(place + ": a .glb file shorter than its header");
  std::memcpy(&length, bytes.data() + 12, 4);
  std::memcpy(&type, bytes.data() + 16, 4);
  if (type != kJsonChunk || length > bytes.size() - kGlbHeaderBytes) {
    throw InputError(place + ": a .glb file without its JSON chunk");
  }
  return bytes.substr(kGlbHeaderBytes, length);
}

}  // namespace

nlohmann::json gltfJson(std::string_view bytes, const std::string& place) {
  nlohmann::json doc = nlohmann::json::parse(jsonText(bytes, place), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) throw InputError(place + ": not glTF 2.0 JSON");
  return doc;
}

}  // namespace glint
