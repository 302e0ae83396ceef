// libFuzzer target: the scene loader from memory (JSON text, with a textured
// OBJ, its MTL and a texture available to name). Bad input must be an
// InputError naming its place; nothing else may escape.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/base/error.h"
#include "common/scene/scene_load.h"
#include "tests/fuzz/fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  glint::MemorySource files;
  glint::fuzz::addFuzzFiles(files);
  const glint::LoadLimits limits = glint::fuzz::smallLimits();
  try {
    (void)glint::loadScene(std::string_view(reinterpret_cast<const char*>(data), size), files, limits);
  } catch (const glint::InputError&) {
  }
  return 0;
}
