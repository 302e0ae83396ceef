#pragma once

namespace glint::bench {

// Glint's BVH beside Embree 3 (issue 14's peer) on the same rays: a terrain
// of 1,000,000 triangles, primary rays of a 1024 x 768 view and incoherent
// rays (from each primary hit in a random direction), traced one at a time
// on one thread by Bvh::intersect and by rtcIntersect1; the builds on every
// hardware thread. Prints medians and ratios, and how often the two agree.
// Built only where Debian's libembree-dev is installed (`make bench`
// installs it; the project itself does not link Embree); otherwise says so.
void embreeSection(bool quick, int runs);

}  // namespace glint::bench
