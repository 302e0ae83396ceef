#pragma once

#include "common/geometry/geometry.h"

namespace glint {

// Vertex normals for a mesh that has none (a mesh's "smooth": ANGLE): each
// corner of a face gets the area-weighted mean of the normals of the faces
// around its position whose normals lie within `creaseDegrees` of the face's
// own, so that edges sharper than the angle stay sharp. Vertices at the same
// position are one point (an OBJ splits them by uv); a vertex whose corners
// get different normals is split. Faces keep their winding.
void smoothNormals(MeshInput& mesh, float creaseDegrees);

}  // namespace glint
