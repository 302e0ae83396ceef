#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include "common/scene/load_limits.h"

namespace glint {

// An OBJ file's data as the mesh builder needs it: its vertex attributes,
// the materials of its mtllib, and its faces as triangles in file order,
// every corner checked against the attributes the file has.
struct ObjTriangles {
  tinyobj::attrib_t attrib;  // vertices (xyz), normals (xyz), texcoords (uv), colors (rgb: obj_colors.h)
  std::vector<tinyobj::material_t> materials;
  std::vector<tinyobj::index_t> corners;  // three a triangle, zero-based; normal, texcoord -1: none
  std::vector<int> materialOf;            // a triangle's index in `materials`, -1: none
  std::size_t pieces = 1;                 // how many pieces the text was read in at once
};

// Parses OBJ text (and the text of its mtllib, "" for none) with
// tinyobjloader's line parser. Triangles and quads (split along the shorter
// diagonal, as tinyobjloader's LoadObj does) are read through its callback
// interface, which builds no per-face objects; a file with a larger polygon
// goes through LoadObj, whose ear clipping triangulates it. Errors (a face
// naming data the file lacks, a limit exceeded) are InputErrors that start
// with `where`. A large text is read in `pieces` at once (0: one a
// hardware thread, for every 4 MiB), cut after lines, and joined into what
// one read gives; a file whose later pieces use relative indices, or that
// fails, is read again whole.
ObjTriangles parseObjTriangles(const std::string& text, const std::string& mtlText,
                               const LoadLimits& limits, const std::string& where,
                               std::size_t pieces = 0);

}  // namespace glint
