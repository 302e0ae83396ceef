#pragma once

namespace glint {

// x^y for floats, computed from IEEE additions, multiplications and
// divisions alone (in double, with tables made the same way), so that every
// machine gives the same bits. glibc's powf picks a
// version with fused multiply-adds at run time on CPUs that have FMA, and
// the two versions disagree in about one call of 15 million (its FMA
// version, for one, rounds pow(0x1.b5d6ep-1, 0x1.5afb9cp+7) one ulp off the
// nearest float): a specular term or an sRGB byte, and so an image, would
// then depend on the machine (docs/numerics.md).
//
// For finite x > 0 and finite y: within 2^-40 of x^y relative before the
// final rounding to float, so the nearest float but where x^y lies closer
// than that to the midpoint of two floats. Elsewhere (zero, negative,
// infinite or NaN operands) std::pow's special values, which need no
// arithmetic.
float power(float x, float y);

// e^x for floats, the same way (the gaussian filter's table: glibc's expf
// is picked at run time too). For finite x: within 2^-40 of e^x relative
// before the rounding to float; infinities and NaN as std::exp.
float exponential(float x);

// x^(1/3) the same way, and faster than power(x, 1/3): Halley's method in
// double from a guess made of x's bits. For finite x >= 0: within 2^-40 of
// the cube root relative before the rounding to float; elsewhere as std::cbrt.
float cubeRoot(float x);

// 2^x for floats (an exposure's scale) from glibc's double exp2, which it
// does not pick at run time; its exp2f it does, as powf.
float twoToThe(float x);

}  // namespace glint
