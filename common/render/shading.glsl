// The direct light's terms, written once in the subset GLSL 3.30 and C++
// share: the tracer compiles them (common/render/shading.h, inline, with GLM's
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
