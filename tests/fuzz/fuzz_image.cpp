// libFuzzer target: image textures (PNG, BMP, JPEG, TGA, Radiance HDR, OpenEXR)
// decoded from memory, with the texture and scene limits a server would
// apply.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/base/error.h"
#include "common/scene/image_decode.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  glint::LoadLimits limits;
  limits.maxTexturePixels = std::size_t{1} << 22;
  limits.maxSceneBytes = std::size_t{64} << 20;
  glint::SceneBudget budget(limits);
  try {
    const glint::Image image =
        glint::decodeImage(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz", budget);
    if (image.rgb.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3) {
      __builtin_trap();  // a decoded image must hold what its size says
    }
  } catch (const glint::InputError&) {
  }
  return 0;
}
