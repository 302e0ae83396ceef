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

// The irradiance field (common/render/irradiance_field.h): probes on a grid,
// each holding the indirect light arriving at it as irradiance in
// spherical harmonics to order 2 and, in an equal-area octahedral map, the
// distances its rays travelled (mean and mean square, per texel).

// atan(x) for x in [0, 1], within 2e-6 rad: a polynomial, the same bits in
// C++ on every machine (no libm), close enough to pick a map's texel.
SHARED float atanUnit(float x) {
  float x2 = x * x;
  return x * (0.99997726f + x2 * (-0.33262347f + x2 * (0.19354346f + x2 * (-0.11643287f +
         x2 * (0.05265332f - 0.01172120f * x2)))));
}

// The point in [0, 1]^2 of unit direction d in the equal-area octahedral
// map (Clarberg 2008: equal areas of the sphere, equal areas of the square).
SHARED vec2 octahedralPoint(vec3 d) {
  vec3 a = abs(d);
  float r = sqrt(max(1.0f - a.z, 0.0f));
  float big = max(a.x, a.y);
  float small = min(a.x, a.y);
  float phi = big > 0.0f ? atanUnit(small / big) * 0.63661977f : 0.0f;  // 2 / pi
  if (a.x < a.y) phi = 1.0f - phi;
  float v = phi * r;
  float u = r - v;
  if (d.z < 0.0f) {
    float w = u;
    u = 1.0f - v;
    v = 1.0f - w;
  }
  u = d.x < 0.0f ? -u : u;
  v = d.y < 0.0f ? -v : v;
  return vec2(u, v) * 0.5f + 0.5f;
}

// Basis function k (0 to 8) of the real spherical harmonics to order 2 at
// unit n (Ramamoorthi and Hanrahan 2001's constants).
SHARED float shBasis(int k, vec3 n) {
  if (k == 0) return 0.282095f;
  if (k == 1) return 0.488603f * n.y;
  if (k == 2) return 0.488603f * n.z;
  if (k == 3) return 0.488603f * n.x;
  if (k == 4) return 1.092548f * n.x * n.y;
  if (k == 5) return 1.092548f * n.y * n.z;
  if (k == 6) return 0.315392f * (3.0f * n.z * n.z - 1.0f);
  if (k == 7) return 1.092548f * n.x * n.z;
  return 0.546274f * (n.x * n.x - n.y * n.y);
}

// The cosine lobe's factor for order l's coefficients of the radiance:
// irradiance E(n) = sum_k A_l(k) L_k Y_k(n), with A_0 = pi, A_1 = 2 pi / 3,
// A_2 = pi / 4.
SHARED float cosineLobe(int k) { return k == 0 ? 3.14159265f : (k < 4 ? 2.09439510f : 0.78539816f); }

// A probe's share of a point's light before its visibility: the trilinear
// weight t, times how far the probe lies on the normal's side (1 in front,
// 0.2 behind: DDGI's smooth backface term, Majercik et al. 2019).
SHARED float probeShare(float t, vec3 toProbe, vec3 n) {
  float facing = (dot(toProbe, n) + 1.0f) * 0.5f;
  return t * (facing * facing + 0.2f);
}

// Whether the probe sees a point at distance d, as its map's texel toward
// the point says: 1 nearer than the mean distance its rays travelled, else
// Chebyshev's bound var / (var + (d - mean)^2), cubed, as DDGI's
// (moments: the mean and the mean square; minVariance keeps a flat texel's
// bound from a step); 0 where that is at most 1/1000, about hidden (a
// probe across a wall keeps no weight to leak its room's light with).
SHARED float probeVisibility(vec2 moments, float d, float minVariance) {
  if (d <= moments.x) return 1.0f;
  float variance = max(moments.y - moments.x * moments.x, minVariance);
  float away = d - moments.x;
  float bound = variance / (variance + away * away);
  float v = bound * bound * bound;
  return v > 0.001f ? v : 0.0f;
}

// Whether a probe's visibility leaves it in doubt whether the probe sees
// the point: neither about seen (0.9) nor hidden (probeVisibility's 0). A
// point near a thin wall or in an object's contact shadow is such for the
// probes across: the coarse map blurs the edge between what they see and
// what they do not, and blending them would leak their light.
SHARED bool visibilityInDoubt(float v) { return v > 0.0f && v < 0.9f; }

// A probe's irradiance toward unit normal n from its coefficients c (each
// A_l L_k), never below zero (order 2 rings slightly under a light that
// arrives from one side only).
SHARED vec3 shIrradiance(const vec3 c[9], vec3 n) {
  vec3 e = vec3(0.0f);
  for (int k = 0; k < 9; ++k) e += c[k] * shBasis(k, n);
  return max(e, vec3(0.0f));
}

// The sum of a material's lobe weights under path transport, for a surface
// of colour c (the material's times its texture): the largest channel of c
// x diffuse (never below zero) plus specular, reflectivity and
// transparency. Where it exceeds 1, every lobe is divided by it (energy
// conserving: common/render/bsdf.h's lobeWeights).
SHARED float lobeSum(vec3 c, float diffuse, float specular, float reflectivity, float transparency) {
  vec3 a = max(c * diffuse, vec3(0.0f));
  return max(a.x, max(a.y, a.z)) + specular + reflectivity + transparency;
}

// The diffuse albedo under path transport: c x diffuse, never below zero,
// renormalised by lobeSum.
SHARED vec3 diffuseAlbedo(vec3 c, float diffuse, float specular, float reflectivity, float transparency) {
  vec3 a = max(c * diffuse, vec3(0.0f));
  float sum = lobeSum(c, diffuse, specular, reflectivity, transparency);
  return sum > 1.0f ? a / sum : a;
}

// The normalised Phong lobe's weight under path transport: `specular`,
// renormalised by lobeSum.
SHARED float specularWeight(vec3 c, float diffuse, float specular, float reflectivity, float transparency) {
  float sum = lobeSum(c, diffuse, specular, reflectivity, transparency);
  return sum > 1.0f ? specular / sum : specular;
}

// What the diffuse and the normalised Phong lobes (bsdf.h: f = albedo / pi
// + specular (h + 2) / (2 pi) (V . R)^h) reflect toward v of the light
// `arriving` from unit direction l, times pi: pi f (N . L), so that a delta
// light of intensity I (path transport's pi I) gives I times this. Zero
// when the light is behind the surface.
SHARED vec3 lobesReflect(vec3 arriving, vec3 albedo, float specular, float h, vec3 n, vec3 l, vec3 v) {
  float nl = dot(n, l);
  if (nl <= 0.0f) return vec3(0.0f);
  vec3 f = albedo;
  if (specular > 0.0f) {
    vec3 r = 2.0f * nl * n - l;
    float vr = dot(v, r);
    if (vr > 0.0f) f += vec3(specular * (h + 2.0f) * 0.5f * pow(vr, h));
  }
  return arriving * f * nl;
}

// atan2(y, x) for y >= 0, in [0, pi], by atanUnit: the same bits in C++ on
// every machine.
SHARED float angleOf(float y, float x) {
  float ax = abs(x);
  float a = y <= ax ? (ax > 0.0f ? atanUnit(y / ax) : 0.0f) : 1.57079633f - atanUnit(ax / y);
  return x < 0.0f ? 3.14159265f - a : a;
}

// v over its length; zero for zero.
SHARED vec3 unitOf(vec3 v) {
  float l = length(v);
  return l > 0.0f ? v / l : vec3(0.0f);
}

// One edge's term of Lambert's closed form for a polygon's irradiance: the
// angle between the unit directions u and w to its ends times the cosine
// between n and the normal of their plane.
SHARED float edgeTerm(vec3 u, vec3 w, vec3 n) {
  vec3 normal = cross(u, w);
  float s = length(normal);
  return s > 0.0f ? angleOf(s, dot(u, w)) * dot(n, normal) / s : 0.0f;
}

// Where the segment from u to w crosses the plane of n through the origin,
// u at height hu above it and w at hw, of the other sign.
SHARED vec3 horizonPoint(vec3 u, vec3 w, float hu, float hw) { return u + (hu / (hu - hw)) * (w - u); }

// Twice the irradiance of unit radiance from the triangle a, b, c (from
// the receiver at the origin, the one of them whose side of n's plane
// differs from the others' first): the part in front of n's plane, a
// triangle (a in front) or a quadrilateral (a behind).
SHARED float clippedTerms(vec3 a, vec3 b, vec3 c, vec3 n) {
  float ha = dot(a, n);
  vec3 ab = unitOf(horizonPoint(a, b, ha, dot(b, n)));
  vec3 ca = unitOf(horizonPoint(c, a, dot(c, n), ha));
  if (ha > 0.0f) {
    vec3 ua = unitOf(a);
    return edgeTerm(ua, ab, n) + edgeTerm(ab, ca, n) + edgeTerm(ca, ua, n);
  }
  vec3 ub = unitOf(b);
  vec3 uc = unitOf(c);
  return edgeTerm(ab, ub, n) + edgeTerm(ub, uc, n) + edgeTerm(uc, ca, n) + edgeTerm(ca, ab, n);
}

// The irradiance a surface at p of unit normal n receives, unshadowed, from
// the triangle a, b, c radiating radiance L from both sides (an emitter of
// common/render/emitter_patches.h): Lambert's closed form for a polygon,
// half the sum over its edges of the angle each spans from p times the
// cosine between n and the normal of the plane through p and that edge,
// the triangle first clipped to the side n faces.
SHARED vec3 triangleIrradiance(vec3 L, vec3 a, vec3 b, vec3 c, vec3 p, vec3 n) {
  a = a - p;
  b = b - p;
  c = c - p;
  bool fa = dot(a, n) > 0.0f;
  bool fb = dot(b, n) > 0.0f;
  bool fc = dot(c, n) > 0.0f;
  float sum = 0.0f;
  if (fa && fb && fc) {
    vec3 ua = unitOf(a);
    vec3 ub = unitOf(b);
    vec3 uc = unitOf(c);
    sum = edgeTerm(ua, ub, n) + edgeTerm(ub, uc, n) + edgeTerm(uc, ua, n);
  } else if (fb == fc && fa != fb) {
    sum = clippedTerms(a, b, c, n);
  } else if (fa == fc && fb != fa) {
    sum = clippedTerms(b, c, a, n);
  } else if (fa == fb && fc != fa) {
    sum = clippedTerms(c, a, b, n);
  }
  return L * (0.5f * abs(sum));
}
