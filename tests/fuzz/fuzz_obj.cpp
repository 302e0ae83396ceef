// libFuzzer target: the OBJ/MTL loader. The input is an OBJ file, optionally
// followed by "\n#MTL\n" and the MTL file its mtllib names (m.mtl); a texture
// tex.bmp is there to name.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "common/obj_load.h"
#include "tests/fuzz/fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string separator = "\n#MTL\n";
  const std::size_t at = input.find(separator);
  glint::MemorySource files;
  files.add("m.obj", input.substr(0, at));
  if (at != std::string::npos) files.add("m.mtl", input.substr(at + separator.size()));
  files.add("tex.bmp", glint::fuzz::tinyBmp());
  const glint::LoadLimits limits = glint::fuzz::smallLimits();
  glint::SceneBudget budget(limits);
  try {
    (void)glint::loadObj(files, "m.obj", "fuzz", budget, true);
  } catch (const glint::InputError&) {
  }
  return 0;
}
