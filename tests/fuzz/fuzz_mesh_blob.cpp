// libFuzzer target: the imported-mesh blob a server reads in place of a glTF
// or PLY file (common/scene/mesh_blob.h). The input is the blob.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/base/error.h"
#include "common/scene/mesh_blob.h"
#include "tests/fuzz/fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const glint::LoadLimits limits = glint::fuzz::smallLimits();
  glint::SceneBudget budget(limits);
  try {
    (void)glint::decodeMeshBlob(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz", budget);
  } catch (const glint::InputError&) {
  }
  return 0;
}
