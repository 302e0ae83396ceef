#pragma once

namespace glint {

// The sine and the cosine of a float angle in radians.
struct SineCosine {
  float sin;
  float cos;
};

// sin x and cos x from IEEE additions, multiplications and divisions alone
// (in double), so that every machine gives the same bits: glibc picks sinf
// and cosf at run time (versions with fused multiply-adds on CPUs that have
// them, docs/numerics.md), and a transform's rotation moves every vertex of
// a mesh by them. For |x| <= 2^20: within 2^-40 of the exact values
// relative before the rounding to float, so the nearest floats but where
// one lies that close to the midpoint of two floats. Beyond, and for
// infinities and NaN, std::sin and std::cos.
SineCosine sineCosine(float x);

// sin and cos of 2 pi u, for u a fraction of a turn in [0, 1]: in float
// alone (quarter turns taken off exactly, then a series to 1e-10), within
// 2^-23 of the exact values and exact at the quarter turns, the same bits
// on every machine. A sampler's azimuth, where sineCosine's double-precision
// reduction is more than a direction needs.
SineCosine turn(float u);

}  // namespace glint
