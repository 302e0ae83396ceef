// libFuzzer target: image textures (PNG, BMP, JPEG, TGA, Radiance HDR, OpenEXR)
// decoded from memory, with the texture and scene limits a server would
// apply; the same bytes as an environment image's linear floats.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/base/error.h"
#include "common/image/image_decode.h"
#include "common/scene/scene_budget.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  glint::LoadLimits limits;
  limits.maxTexturePixels = std::size_t{1} << 22;
  limits.maxSceneBytes = std::size_t{64} << 20;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const auto holdsItsSize = [](int width, int height, std::size_t values) {
    if (values != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
      __builtin_trap();  // a decoded image must hold what its size says
    }
  };
  try {
    glint::SceneBudget budget(limits);
    const glint::Image image = glint::decodeImage(bytes, "fuzz", budget);
    holdsItsSize(image.width, image.height, image.rgb.size());
  } catch (const glint::InputError&) {
  }
  try {
    glint::SceneBudget budget(limits);
    const glint::FloatPixels pixels = glint::decodeLinearImage(bytes, "fuzz", budget);
    holdsItsSize(pixels.width, pixels.height, pixels.rgb.size());
  } catch (const glint::InputError&) {
  }
  return 0;
}
