#pragma once

#include <vector>

#include "common/geometry/geometry.h"
#include "common/geometry/ray.h"

namespace glint::bench {

// A procedural terrain: a gridWidth x gridDepth heightfield of
// 2 gridWidth gridDepth triangles over 100 x 50 units, with hills of a few
// units; flat and wide, like the scenes where the thesis's axis-cycling
// QSplit wastes levels on the thin axis.
Geometry terrain(int gridWidth, int gridDepth);

// A closed sphere of radius about 1 around the origin, n x n quads
// (2 n^2 triangles), its radius rippled by 5 %: the "displaced
// sphere" (n = 700: 980,000 triangles).
MeshInput rippledSphere(int n);

// count rays from 10 to 40 units above the terrain down to random points on
// it, at most 10 units aside (like primary rays of a view from above).
std::vector<Ray> terrainRays(int count, unsigned seed);

// count rays from random points inside the room towards random directions.
std::vector<Ray> roomRays(int count, unsigned seed);

}  // namespace glint::bench
