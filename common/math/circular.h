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

}  // namespace glint
