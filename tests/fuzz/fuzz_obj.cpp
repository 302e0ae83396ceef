// libFuzzer target: the OBJ/MTL loader. The input is an OBJ file, optionally
// followed by "\n#MTL\n" and the MTL file its mtllib names (m.mtl); a texture
// tex.bmp is there to name. The OBJ text is also read in two pieces at
// once, which must give what one read gives (the same triangles or the same
// error); a difference aborts.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "common/base/error.h"
#include "common/scene/obj_faces.h"
#include "common/scene/obj_load.h"
#include "tests/fuzz/fuzz_files.h"

namespace {

// What parseObjTriangles gives, as text: its error, or every number of its
// triangles.
std::string readAs(const std::string& obj, const std::string& mtl, const glint::LoadLimits& limits,
                   std::size_t pieces) {
  try {
    const glint::ObjTriangles t = glint::parseObjTriangles(obj, mtl, limits, "fuzz", pieces);
    std::string out = std::to_string(t.materials.size()) + ";";
    for (const auto* v : {&t.attrib.vertices, &t.attrib.normals, &t.attrib.texcoords}) {
      out.append(reinterpret_cast<const char*>(v->data()), v->size() * sizeof(float)).push_back(';');
    }
    for (const auto& c : t.corners) {
      out += std::to_string(c.vertex_index) + "/" + std::to_string(c.normal_index) + "/" + std::to_string(c.texcoord_index) + " ";
    }
    for (const int m : t.materialOf) out += std::to_string(m) + " ";
    return out;
  } catch (const glint::InputError& e) {
    return std::string("error: ") + e.what();
  }
}

}  // namespace

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
  const std::string obj = input.substr(0, at), mtl = at == std::string::npos ? "" : input.substr(at + separator.size());
  if (readAs(obj, mtl, limits, 2) != readAs(obj, mtl, limits, 1)) std::abort();
  return 0;
}
