#pragma once

#include <string_view>
#include <vector>

namespace glint {

// The vertex colours of an OBJ text, in the extension that writes them after
// a vertex's position (`v x y z r g b`, as MeshLab and tinyobjloader read
// it): r, g, b for each `v` line, in order, when the file's first `v` line
// has them (none otherwise, and without a scan of the rest); a later line
// without them is white.
std::vector<float> objVertexColors(std::string_view text);

}  // namespace glint
