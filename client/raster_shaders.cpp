#include "client/raster_shaders.h"

#include <string>
#include <utility>

namespace glint::gl {

std::string fragmentPrelude(bool stencilExport) {
  std::string prelude = "#version 330\n";
  if (stencilExport) prelude += "#extension GL_ARB_shader_stencil_export : require\n#define STENCIL_EXPORT\n";
  const std::pair<const char*, int> limits[] = {{"MAX_LIGHTS", kMaxLights},
                                                {"MAX_MATERIALS", kMaxMaterials},
                                                {"MAX_TEXTURES", kMaxTextures}};
  for (const auto& [name, value] : limits) prelude.append("#define ").append(name).append(" ").append(std::to_string(value)).append("\n");
  return prelude;
}

// Shared by both fragment shaders, after the prelude: material, texture and
// light data, shadowVisibility() (the shadow maps, client/shadow_maps.h),
// shade(), which mirrors Tracer::shade, and encodeOutput(), which mirrors
// Encoder::byte before the rounding.
const char* const kFragmentShading = R"(
uniform vec3 uEye;
uniform float uFar;            // depth = distance from the eye / uFar (RasterScene::Projection)
uniform float uExposureScale;  // 2^exposure
uniform bool uSrgb;
uniform int uLightCount;
uniform vec3 uLightPosition[MAX_LIGHTS];
uniform vec3 uLightColor[MAX_LIGHTS];
uniform vec3 uLightAttenuation[MAX_LIGHTS];
uniform vec4 uMaterialColor[MAX_MATERIALS];  // rgb, texture index or -1
uniform vec4 uMaterialTerms[MAX_MATERIALS];  // ambient, diffuse, specular, shininess
uniform vec4 uTextureInfo[MAX_TEXTURES];     // type (1 checker, 2 image), checker scale, bilinear, atlas row
uniform vec4 uTextureSize[MAX_TEXTURES];     // image width, height
uniform vec3 uTextureColor0[MAX_TEXTURES];
uniform vec3 uTextureColor1[MAX_TEXTURES];
uniform sampler2D uAtlas;                    // every image texture, stacked rows, RGB float
uniform sampler2DArray uShadowMaps;          // depth: distance from the light / uShadowFar
uniform int uShadowSize;                     // texels a face edge
uniform int uShadowLayer[MAX_LIGHTS];        // the light's first face, -1: no map
uniform float uShadowFar[MAX_LIGHTS];
uniform vec3 uShadowFaceS[6];
uniform vec3 uShadowFaceT[6];
uniform vec3 uShadowFaceM[6];
uniform int uShadowRadius;                   // texels read on each side of a point's own
uniform int uUndecidedStencil;               // the stencil of a pixel the maps cannot decide
uniform bool uSkipMarked;                    // the anti-aliased pass: the tracer's pixels are not shaded
uniform usampler2D uStencilMarks;            // draw()'s StencilMark of each pixel, rows from the top
out vec4 fragColor;
bool gShadowUndecided = false;               // set by shadowVisibility()

// Whether the anti-aliased pass leaves this pixel's samples out: draw()
// marked it, and the tracer's pixel replaces it.
bool skipped() {
  if (!uSkipMarked) return false;
  ivec2 p = ivec2(gl_FragCoord.xy);
  return texelFetch(uStencilMarks, ivec2(p.x, textureSize(uStencilMarks, 0).y - 1 - p.y), 0).r != 0u;
}

vec3 encodeOutput(vec3 linear) {
  vec3 v = clamp(linear * uExposureScale, 0.0, 1.0);
  if (!uSrgb) return v;
  return mix(1.055 * pow(v, vec3(1.0 / 2.4)) - 0.055, 12.92 * v, lessThanEqual(v, vec3(0.0031308)));
}

// The fragment's colour from shade()'s; black where only the marks are
// wanted (shade() still runs for gShadowUndecided, and the compiler drops
// the terms that only the colour needs).
vec4 outputColour(vec3 shaded) {
#ifdef MARKS_ONLY
  return vec4(0.0, 0.0, 0.0, 1.0);
#else
  return vec4(encodeOutput(shaded), 1.0);
#endif
}

vec3 texel(int t, int x, int y) {
  ivec2 size = ivec2(uTextureSize[t].xy);
  x = ((x % size.x) + size.x) % size.x;
  y = ((y % size.y) + size.y) % size.y;
  return texelFetch(uAtlas, ivec2(x, int(uTextureInfo[t].w) + y), 0).rgb;
}

float wrap(float x) {
  float w = x - floor(x);
  return w < 1.0 ? w : 0.0;
}

vec3 textureColor(int t, vec2 uv) {
  if (uTextureInfo[t].x == 1.0) {
    float s = uTextureInfo[t].y;
    float sum = floor(uv.x * s) + floor(uv.y * s);
    return mod(abs(sum), 2.0) == 1.0 ? uTextureColor1[t] : uTextureColor0[t];
  }
  vec2 size = uTextureSize[t].xy;
  float x = wrap(uv.x) * size.x;
  float y = (1.0 - wrap(uv.y)) * size.y;
  if (uTextureInfo[t].z == 0.0) return texel(t, int(x), int(y));
  float fx = x - 0.5, fy = y - 0.5;
  float x0 = floor(fx), y0 = floor(fy);
  float tx = fx - x0, ty = fy - y0;
  int ix = int(x0), iy = int(y0);
  vec3 top = (1.0 - tx) * texel(t, ix, iy) + tx * texel(t, ix + 1, iy);
  vec3 bottom = (1.0 - tx) * texel(t, ix, iy + 1) + tx * texel(t, ix + 1, iy + 1);
  return (1.0 - ty) * top + ty * bottom;
}

// The map texel a direction from the light falls on: x, y and the face.
ivec3 shadowTexel(vec3 v) {
  vec3 a = abs(v);
  int f = a.x >= a.y && a.x >= a.z ? (v.x >= 0.0 ? 0 : 1) : a.y >= a.z ? (v.y >= 0.0 ? 2 : 3) : (v.z >= 0.0 ? 4 : 5);
  vec2 c = vec2(dot(uShadowFaceS[f], v), dot(uShadowFaceT[f], v)) / dot(uShadowFaceM[f], v);
  ivec2 xy = clamp(ivec2(floor((c * 0.5 + 0.5) * float(uShadowSize))), ivec2(0), ivec2(uShadowSize - 1));
  return ivec3(xy, f);
}

// The direction (from the light, not normalized) through a texel's centre
// of a face, or through where such a texel would lie beyond the face's edge.
vec3 shadowTexelDirection(ivec2 xy, int f) {
  vec2 c = (vec2(xy) + 0.5) / float(uShadowSize) * 2.0 - 1.0;
  return uShadowFaceM[f] + c.x * uShadowFaceS[f] + c.y * uShadowFaceT[f];
}

// One texel's vote for shadowVisibility: u its centre's direction from the
// light (not normalized), the tangent plane `plane` away from the light with
// normal ng. Counts the texel in count, and in open unless it holds a surface
// nearer than where u meets the plane (beyond the tolerance of the map's
// float precision); a direction grazing the plane decides nothing.
void shadowVote(int light, ivec3 texel, vec3 u, float plane, vec3 ng, inout int open, inout int count) {
  float len = length(u);
  float cosine = -dot(u, ng) / len;
  if (cosine < 0.01) {
    gShadowUndecided = true;
    return;
  }
  float expected = plane / cosine;
  float tolerance = expected * 1e-4 * (1.0 + 1.0 / cosine);
  float stored = texelFetch(uShadowMaps, ivec3(texel.xy, uShadowLayer[light] + texel.z), 0).r * uShadowFar[light];
  ++count;
  if (stored >= expected - tolerance) ++open;
}

// Whether the light reaches p (ng faces the light): 1 lit, 0 shadowed, by
// the map's texels around p's (across a face's edge onto the next face).
// Each texel's centre direction meets p's tangent plane at a distance from
// the light; a texel holding a nearer surface sees an occluder. All texels
// open: lit; all occluded: shadowed; a mix (a shadow edge, or a receiver
// curving towards the light) or a direction grazing the plane: undecided
// (gShadowUndecided), and the fraction open.
float shadowVisibility(int light, vec3 p, vec3 ng) {
  if (uShadowLayer[light] < 0) return 1.0;
  vec3 v = p - uLightPosition[light];
  ivec3 own = shadowTexel(v);
  float plane = -dot(v, ng);  // the light's distance from p's tangent plane
  int open = 0, count = 0;
  // The texels around p's on p's face (directions step by the face's axes);
  // p within uShadowRadius texels of the face's edge is undecided (its
  // neighbours clamped to the face for the estimate).
  float step = 2.0 / float(uShadowSize);
  vec3 s = step * uShadowFaceS[own.z], t = step * uShadowFaceT[own.z];
  vec3 centre = shadowTexelDirection(own.xy, own.z);
  for (int dy = -uShadowRadius; dy <= uShadowRadius; ++dy) {
    for (int dx = -uShadowRadius; dx <= uShadowRadius; ++dx) {
      ivec2 xy = clamp(own.xy + ivec2(dx, dy), ivec2(0), ivec2(uShadowSize - 1));
      vec2 d = vec2(xy - own.xy);
      shadowVote(light, ivec3(xy, own.z), centre + d.x * s + d.y * t, plane, ng, open, count);
    }
  }
  if (any(lessThan(own.xy, ivec2(uShadowRadius))) || any(greaterThanEqual(own.xy, ivec2(uShadowSize - uShadowRadius)))) {
    gShadowUndecided = true;
  }
  if (open != 0 && open != count) gShadowUndecided = true;
  return count == 0 ? 1.0 : float(open) / float(count);
}

vec3 shade(vec3 p, vec3 ng, vec3 ns, vec2 uv, int material) {
  vec3 toViewer = normalize(uEye - p);
  if (dot(ng, toViewer) < 0.0) ng = -ng;
  float len = length(ns);
  ns = len > 0.0 ? ns / len : ng;
  if (dot(ns, ng) < 0.0) ns = -ns;
  vec4 mc = uMaterialColor[material];
  vec4 terms = uMaterialTerms[material];
  vec3 c = mc.w >= 0.0 ? textureColor(int(mc.w), uv) : mc.rgb;
  vec3 result = c * terms.x;
  if (terms.y <= 0.0 && terms.z <= 0.0) return result;
  for (int i = 0; i < uLightCount; ++i) {
    vec3 toLight = uLightPosition[i] - p;
    float d = length(toLight);
    if (!(d > 0.0)) continue;
    vec3 l = toLight / d;
    if (dot(l, ng) <= 0.0 || dot(l, ns) <= 0.0) continue;
    float visible = shadowVisibility(i, p, ng);
    if (visible == 0.0) continue;
    vec3 a = uLightAttenuation[i];
    vec3 lightI = visible * uLightColor[i] / (a.x + a.y * d + a.z * d * d);
    float nl = dot(ns, l);
    result += lightI * c * (terms.y * nl);
    if (terms.z > 0.0) {
      vec3 r = 2.0 * nl * ns - l;
      float vr = dot(toViewer, r);
      if (vr > 0.0) result += lightI * (terms.z * pow(vr, terms.w));
    }
  }
  return result;
}
)";

const char* const kMeshVertexShader = R"(#version 330
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
layout(location = 3) in vec3 aFaceNormal;
layout(location = 4) in int aMaterial;
uniform mat4 uViewProjection;
out vec3 vPosition;
out vec3 vNormal;
out vec2 vUv;
flat out vec3 vFaceNormal;
flat out int vMaterial;
void main() {
  vPosition = aPosition;
  vNormal = aNormal;
  vUv = aUv;
  vFaceNormal = aFaceNormal;
  vMaterial = aMaterial;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)";

const char* const kMeshFragmentShader = R"(
in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
flat in vec3 vFaceNormal;
flat in int vMaterial;
void main() {
#ifndef TRACED
  if (skipped()) discard;
#endif
  gl_FragDepth = length(vPosition - uEye) / uFar;
#ifdef TRACED
  fragColor = vec4(0.0, 0.0, 0.0, 1.0);
#else
  fragColor = outputColour(shade(vPosition, vFaceNormal, vNormal, vUv, vMaterial));
#ifdef STENCIL_EXPORT
  gl_FragStencilRefARB = gShadowUndecided ? uUndecidedStencil : 0;
#endif
#endif
}
)";

// Spheres are exact on screen: each sphere's bounding box is drawn and each
// fragment casts the eye ray through it against the sphere (the tracer's
// formula), writing the hit's depth; front and back faces of the box give
// the same hit, so the camera may also be inside the box.
const char* const kSphereVertexShader = R"(#version 330
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aSphere;  // centre, radius
layout(location = 2) in int aMaterial;
uniform mat4 uViewProjection;
out vec3 vPosition;
flat out vec4 vSphere;
flat out int vMaterial;
void main() {
  vPosition = aPosition;
  vSphere = aSphere;
  vMaterial = aMaterial;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)";

const char* const kSphereFragmentShader = R"(
in vec3 vPosition;
flat in vec4 vSphere;
flat in int vMaterial;
void main() {
#ifndef TRACED
  if (skipped()) discard;
#endif
  vec3 d = normalize(vPosition - uEye);
  vec3 f = uEye - vSphere.xyz;
  float b = -dot(f, d);
  vec3 l = f + b * d;
  float r2 = vSphere.w * vSphere.w;
  float disc = r2 - dot(l, l);
  if (!(disc >= 0.0)) discard;
  float c = dot(f, f) - r2;
  float q = b + (b < 0.0 ? -sqrt(disc) : sqrt(disc));
  if (q == 0.0) discard;
  float t0 = min(c / q, q), t1 = max(c / q, q);
  float t = t0 > 0.0 ? t0 : t1;
  if (!(t > 0.0)) discard;
  vec3 p = uEye + t * d;
  vec3 n = normalize(p - vSphere.xyz);
  p = vSphere.xyz + vSphere.w * n;
  gl_FragDepth = length(p - uEye) / uFar;
#ifdef TRACED
  fragColor = vec4(0.0, 0.0, 0.0, 1.0);
#else
  float u = atan(n.x, n.z) / (2.0 * 3.14159265);
  float v = acos(clamp(-n.y, -1.0, 1.0)) / 3.14159265;
  vec2 uv = vec2(u < 0.0 ? u + 1.0 : u, v);
  fragColor = outputColour(shade(p, n, n, uv, vMaterial));
#ifdef STENCIL_EXPORT
  gl_FragStencilRefARB = gShadowUndecided ? uUndecidedStencil : 0;
#endif
#endif
}
)";

}  // namespace glint::gl
