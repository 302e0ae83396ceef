#pragma once

#include <string>

namespace glint::bench {

// Glint's BVH beside Embree 3 on the same rays, in four
// scenes: a terrain of 1,000,000 triangles and a closed mesh (a
// rippled sphere of 980,000, seen from inside), both in a 1024 x 768 view,
// and the bunny and the thesis's room from the folder `scenes` (their own
// views and image sizes). Three ray sets each: primary rays; the mirror
// bounces that follow them to depth 5 (incoherent as Glint's reflections are); and
// from each primary hit one ray in a random direction (incoherent as a
// diffuse bounce's, which Glint never casts). Traced one at a time on one
// thread by Bvh::intersect and by rtcIntersect1 (the room's sphere is one
// of Embree's sphere points); the builds on every hardware thread. Prints
// medians and ratios, and how often the two agree. Built only where
// Debian's libembree-dev is installed (`make bench` installs it; the
// project itself does not link Embree); otherwise says so.
void embreeSection(const std::string& scenes, bool quick, int runs);

}  // namespace glint::bench
