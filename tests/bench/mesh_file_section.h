#pragma once

namespace glint::bench {

// Reading a large OBJ (target: a 1M-triangle OBJ in under 0.4 s): a
// displaced sphere of 980,000 triangles written to a temporary folder, read
// from disk by Glint's loader (the scene's path: tinyobjloader's parse, then
// the vertices grouped), by tinyobjloader's parse alone, and by Assimp
// (triangulation only, one vertex per corner), in the same run; medians.
void meshFileSection(bool quick, int runs);

}  // namespace glint::bench
