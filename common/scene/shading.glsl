// The shading functions, written once in the subset GLSL 3.30 and C++
// share: the tracer compiles them (common/scene/shading.h, inline, with GLM's
// vec3 and the exact power() for pow) and the raster's fragment shaders get
// them as source (client/raster/raster_shaders.cpp). Floats only: every
// literal has its f, so that C++ computes in float as GLSL does. No
// includes, no preprocessor lines: SHARED is `inline` in C++ and nothing in
// GLSL.
//
// The thesis's Phong model, term by term (thesis digest, "Lighting"):
//   I   = I_A + sum_i (I_D,i + I_S,i)
//   I_A = C r_A
//   I_D = I_L C r_D (N . L)
//   I_S = I_L r_S (V . R)^h,  R = 2 (N . L) N - L
// N, L, V unit; L towards the light, V towards the viewer.

SHARED vec3 phongAmbient(vec3 c, float rA) { return c * rA; }

// Zero when the light is behind the surface (N . L <= 0).
SHARED vec3 phongDiffuse(vec3 lightI, vec3 c, float rD, vec3 n, vec3 l) {
  float nl = dot(n, l);
  if (nl <= 0.0f) return vec3(0.0f);
  return lightI * c * (rD * nl);
}

// Zero when N . L <= 0 or V . R <= 0.
SHARED vec3 phongSpecular(vec3 lightI, float rS, float h, vec3 n, vec3 l, vec3 v) {
  float nl = dot(n, l);
  if (nl <= 0.0f) return vec3(0.0f);
  vec3 r = 2.0f * nl * n - l;
  float vr = dot(v, r);
  if (vr <= 0.0f) return vec3(0.0f);
  return lightI * (rS * pow(vr, h));
}

// I_L = color / (c + l d + q d^2) for attenuation (c, l, q) at distance d.
SHARED vec3 attenuate(vec3 color, vec3 attenuation, float d) {
  return color / (attenuation.x + attenuation.y * d + attenuation.z * d * d);
}

// A spot light's share at unit direction l from the surface towards the
// light (KHR_lights_punctual's falloff): with c the cosine of the angle
// between the light's axis and -l, t = (c - cosOuter) / (cosInner -
// cosOuter) clamped to [0, 1], the share is t^2 (1 inside the inner cone, 0
// outside the outer one; equal cones: a hard edge, the ramp HARD_SPOT_EDGE
// wide in cosine).
SHARED float spotFactor(vec3 axis, float cosInner, float cosOuter, vec3 l) {
  float c = -dot(axis, l);
  float t = clamp((c - cosOuter) / max(cosInner - cosOuter, HARD_SPOT_EDGE), 0.0f, 1.0f);
  return t * t;
}

// A texture coordinate in [0, 1] (repeat: [0, 1)) as the wrap mode (WRAP_*,
// TextureWrap) reads it.
SHARED float wrapped(float x, int mode) {
  if (mode == WRAP_MIRRORED_REPEAT) {
    float w = x - 2.0f * floor(x * 0.5f);  // [0, 2): forwards, then back
    return w <= 1.0f ? w : 2.0f - w;
  }
  if (mode == WRAP_CLAMP_TO_EDGE) return clamp(x, 0.0f, 1.0f);
  float w = x - floor(x);
  return w < 1.0f ? w : 0.0f;
}

// i mod n in [0, n) for any i (GLSL leaves % of a negative operand
// undefined; Mesa's llvmpipe took -1 % 3 as 0).
SHARED int floorMod(int i, int n) { return i >= 0 ? i % n : n - 1 - (-1 - i) % n; }

// The texel index i of a row or column of n reads, by the wrap mode.
SHARED int wrappedIndex(int i, int n, int mode) {
  if (mode == WRAP_MIRRORED_REPEAT) {
    int k = floorMod(i, 2 * n);
    return k < n ? k : 2 * n - 1 - k;
  }
  if (mode == WRAP_CLAMP_TO_EDGE) return clamp(i, 0, n - 1);
  return floorMod(i, n);
}

// Where uv reads in an image of `size` texels, in texels: x to the right, y
// down from the top row (u runs right and v up, so v = 1 is row 0); wrap
// holds the wrap modes along u and v.
SHARED vec2 imagePoint(vec2 uv, ivec2 wrap, vec2 size) {
  return vec2(wrapped(uv.x, wrap.x) * size.x, (1.0f - wrapped(uv.y, wrap.y)) * size.y);
}

// The bilinear filter at image point p reads the four texel centres (at
// i + 0.5) around it: the first of them (the others are one texel right,
// below, and both) ...
SHARED ivec2 bilinearCorner(vec2 p) { return ivec2(floor(p - 0.5f)); }

// ... and blends them: c00 at the corner, c10 right of it, c01 below it.
SHARED vec3 bilinearBlend(vec3 c00, vec3 c10, vec3 c01, vec3 c11, vec2 p) {
  vec2 f = p - 0.5f;
  vec2 t = f - floor(f);
  vec3 top = (1.0f - t.x) * c00 + t.x * c10;
  vec3 bottom = (1.0f - t.x) * c01 + t.x * c11;
  return (1.0f - t.y) * top + t.y * bottom;
}
