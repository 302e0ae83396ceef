#include "client/raster/raster_shaders.h"

#include <cstdio>
#include <string>

#include "client/raster/field_light.h"
#include "client/raster/shading_source.h"
#include "common/scene/shading.h"
#include "common/scene/light.h"
#include "common/scene/texture.h"

namespace glint::gl {

int ShaderVariant::key() const {
  return (sphere ? 1 : 0) | (traced ? 2 : 0) | static_cast<int>(texture) << 2 | (lit ? 16 : 0) |
         (specular ? 32 : 0) | (shadows ? 64 : 0) | (srgb ? 128 : 0) | (depthMap ? 256 : 0) | (emits ? 512 : 0) |
         static_cast<int>(emission) << 10 | (vertexColors ? 4096 : 0) | (spotLights ? 8192 : 0) |
         (directionalLights ? 16384 : 0) | (field ? 32768 : 0);
}

std::string ShaderVariant::defines() const {
  std::string d;
  const auto define = [&d](bool on, const char* name) {
    if (on) d.append("#define ").append(name).append("\n");
  };
  define(traced, "TRACED");
  define(texture == TextureKind::kChecker, "TEXTURE_CHECKER");
  define(texture == TextureKind::kNearest || texture == TextureKind::kBilinear, "TEXTURE_IMAGE");
  define(texture == TextureKind::kBilinear, "TEXTURE_BILINEAR");
  define(emits, "EMISSIVE");
  define(emission == TextureKind::kNearest || emission == TextureKind::kBilinear, "EMISSION_IMAGE");
  define(emission == TextureKind::kBilinear, "EMISSION_BILINEAR");
  define(vertexColors, "VERTEX_COLORS");
  define(lit, "LIT");
  define(specular, "SPECULAR");
  define(shadows, "SHADOWS");
  define(srgb, "SRGB");
  define(depthMap, "DEPTH_MAP");
  define(spotLights, "SPOT_LIGHTS");
  define(directionalLights, "DIRECTIONAL_LIGHTS");
  define(field, "FIELD");
  return d;
}

namespace {

// A float as GLSL reads it back to the same value.
std::string floatLiteral(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9e", static_cast<double>(v));
  return text;
}

}  // namespace

std::string fragmentPrelude(const ShaderVariant& variant) {
  const auto define = [](const char* name, const std::string& value) {
    return "#define " + std::string(name) + " " + value + "\n";
  };
  return "#version 330\n" + define("MAX_LIGHTS", std::to_string(kMaxLights)) +
         define("AREA_POINT_FIELDS", std::to_string(kAreaPointFields)) +
         define("AREA_POINTS_PER_ROW", std::to_string(kAreaPointsPerRow)) +
         define("SHADOW_RADIUS", std::to_string(kShadowRadius)) +
         define("LIGHT_SPOT", std::to_string(static_cast<int>(LightType::kSpot))) +
         define("LIGHT_DIRECTIONAL", std::to_string(static_cast<int>(LightType::kDirectional))) +
         define("WRAP_MIRRORED_REPEAT", std::to_string(static_cast<int>(TextureWrap::kMirroredRepeat))) +
         define("WRAP_CLAMP_TO_EDGE", std::to_string(static_cast<int>(TextureWrap::kClampToEdge))) +
         define("HARD_SPOT_EDGE", floatLiteral(kHardSpotEdge)) +
         define("FIELD_PROBE_TEXELS", std::to_string(kFieldProbeTexels)) +
         define("FIELD_SH_TEXELS", std::to_string(kFieldShTexels)) +
         define("FIELD_PROBES_PER_ROW", std::to_string(kFieldProbesPerRow)) +
         define("FIELD_MAP_SIDE", std::to_string(IrradianceField::kMapSide)) +
         define("FIELD_DECIDED_SHARE", floatLiteral(IrradianceField::kDecidedShare)) +
         define("FIELD_DOUBT_SHARE", floatLiteral(IrradianceField::kDoubtShare)) +
         define("MAX_EMITTERS", std::to_string(EmitterPatches::kMaxPatches)) + variant.defines() + define("SHARED", "") +
         kSharedShading;
}

// Shared by both fragment shaders, after the prelude: the material's and the
// lights' uniforms, shadowVisibility() (the shadow maps,
// client/raster/shadow_maps.h), shade(), which mirrors Tracer::shade, and
// encodeOutput(), which mirrors Encoder::byte before the rounding.
const char* const kFragmentShading = R"(
uniform vec3 uEye;
uniform float uFar;            // a shadow map's depth = distance from the eye / uFar
uniform float uExposureScale;  // 2^exposure
uniform int uLightCount;
uniform vec3 uLightPosition[MAX_LIGHTS];
uniform vec3 uLightColor[MAX_LIGHTS];
uniform vec3 uLightAttenuation[MAX_LIGHTS];
uniform int uLightKind[MAX_LIGHTS];          // LightType: point, spot or directional
uniform vec3 uLightDirection[MAX_LIGHTS];    // unit: a spot's axis, a directional light's travel
uniform vec2 uLightCone[MAX_LIGHTS];         // a spot's cosInner, cosOuter
uniform int uAreaCount;                      // area lights' points (AreaLightPoints' centres), sphere lights' centres
// Their texture (RGB float, read exactly): per point its position, colour,
// attenuation and normal (towards the light's lit side; zero: every side).
uniform sampler2D uAreaPoints;
uniform vec3 uColor;                         // the material's colour (times its texture)
uniform vec4 uTerms;                         // ambient, diffuse, specular, shininess
uniform vec3 uCheckerColor0;
uniform vec3 uCheckerColor1;
uniform float uCheckerScale;
uniform sampler2D uImage;                    // the material's image texture, RGB float, read with texelFetch
uniform mat3x2 uImageTransform;              // the texture's uv transform (Texture::transform)
uniform ivec2 uImageWrap;                    // its wrap modes along u and v (TextureWrap)
uniform vec3 uEmission;                      // the material's emission (times its emission image)
uniform sampler2D uEmissionImage;            // as uImage
uniform mat3x2 uEmissionTransform;
uniform ivec2 uEmissionWrap;
uniform sampler2DArray uShadowMaps;          // depth: distance from the light / uShadowFar
uniform int uShadowSize;                     // texels a face edge
uniform int uShadowLayer[MAX_LIGHTS];        // the light's first face, -1: no map
uniform float uShadowFar[MAX_LIGHTS];
uniform vec3 uShadowAxisS[MAX_LIGHTS];       // a directional light's layer: its axes
uniform vec3 uShadowAxisT[MAX_LIGHTS];
uniform vec3 uShadowCentre;                  // the sphere the directional layers span
uniform float uShadowRadius;
uniform vec3 uDepthAxis;                     // a depth map's: non-zero for a directional light's
uniform vec3 uShadowFaceS[6];
uniform vec3 uShadowFaceT[6];
uniform vec3 uShadowFaceM[6];
uniform vec2 uOtherLobes;                    // the material's reflectivity and transparency (diffuseAlbedo)
uniform sampler2D uField;                    // the field's probes (client/raster/field_light.h)
uniform vec3 uFieldOrigin;                   // probe (0, 0, 0)
uniform vec3 uFieldStep;                     // between neighbouring probes
uniform ivec3 uFieldCounts;                  // probes along each axis
uniform vec3 uEmitters[4 * MAX_EMITTERS];    // per emitting triangle: its corners, its emission
uniform int uEmitterCount;
uniform bool uMarkUndecided;                 // a pixel the maps cannot decide is traced (rule auto)
uniform bool uSelfShadowing;                 // the tracer casts shadow rays (EffectPlan::shadows)
layout(location = 0) out vec4 fragColor;
layout(location = 1) out uint fragSurface;   // object << 2 | PixelMark
bool gShadowUndecided = false;               // set by shadowVisibility() and behindTriangle()
bool gFieldUndecided = false;                // set by fieldIrradiance()
vec3 gLobeAlbedo;                            // with a field, path transport's lobe weights (set by shade)
float gLobeSpecular;

vec3 encodeOutput(vec3 linear) {
  vec3 v = clamp(linear * uExposureScale, 0.0, 1.0);
#ifdef SRGB
  return mix(1.055 * pow(v, vec3(1.0 / 2.4)) - 0.055, 12.92 * v, lessThanEqual(v, vec3(0.0031308)));
#else
  return v;
#endif
}

// The surface value of a fragment OpenGL shades: traced where the shadow
// maps or the field could not decide (and the rule says so).
uint surfaceOf(int object) {
  return uint(object) << 2 | ((gShadowUndecided || gFieldUndecided) && uMarkUndecided ? 2u : 0u);
}

#if defined(TEXTURE_IMAGE) || defined(EMISSION_IMAGE)
vec3 texel(sampler2D image, ivec2 wrap, int x, int y) {
  ivec2 size = textureSize(image, 0);
  return texelFetch(image, ivec2(wrappedIndex(x, size.x, wrap.x), wrappedIndex(y, size.y, wrap.y)), 0).rgb;
}

// An image texture at uv, as Texture::evaluate reads it (`bilinear` is a
// constant at each call, so the compiler keeps one filter).
vec3 imageColour(sampler2D image, ivec2 wrap, vec2 uv, bool bilinear) {
  vec2 p = imagePoint(uv, wrap, vec2(textureSize(image, 0)));
  if (!bilinear) return texel(image, wrap, int(p.x), int(p.y));
  ivec2 c = bilinearCorner(p);
  return bilinearBlend(texel(image, wrap, c.x, c.y), texel(image, wrap, c.x + 1, c.y),
                       texel(image, wrap, c.x, c.y + 1), texel(image, wrap, c.x + 1, c.y + 1), p);
}
#endif

vec3 textureColour(vec2 given) {
  vec2 uv = uImageTransform * vec3(given, 1.0);
#if defined(TEXTURE_CHECKER)
  float sum = floor(uv.x * uCheckerScale) + floor(uv.y * uCheckerScale);
  return mod(abs(sum), 2.0) == 1.0 ? uCheckerColor1 : uCheckerColor0;
#elif defined(TEXTURE_BILINEAR)
  return imageColour(uImage, uImageWrap, uv, true);
#elif defined(TEXTURE_IMAGE)
  return imageColour(uImage, uImageWrap, uv, false);
#else
  return vec3(1.0);
#endif
}

// The surface's own light, as the tracer's emitted().
vec3 emitted(vec2 given) {
  vec2 uv = uEmissionTransform * vec3(given, 1.0);
#if defined(EMISSION_BILINEAR)
  return uEmission * imageColour(uEmissionImage, uEmissionWrap, uv, true);
#elif defined(EMISSION_IMAGE)
  return uEmission * imageColour(uEmissionImage, uEmissionWrap, uv, false);
#else
  return uEmission;
#endif
}

#ifdef VERTEX_COLORS
in vec3 vColor;  // the mesh's vertex colours, interpolated
#endif

// The material's colour times its texture (times the vertex colours), as
// the tracer's shade() takes it.
vec3 surfaceColour(vec2 uv) {
#if defined(TEXTURE_CHECKER) || defined(TEXTURE_IMAGE)
  vec3 base = uColor * textureColour(uv);
#else
  vec3 base = uColor;
#endif
#ifdef VERTEX_COLORS
  return base * vColor;
#else
  return base;
#endif
}

#ifdef SHADOWS
// The map texel a direction from the light falls on: x, y and the face.
ivec3 shadowTexel(vec3 v) {
  vec3 a = abs(v);
  int f = a.x >= a.y && a.x >= a.z ? (v.x >= 0.0 ? 0 : 1) : a.y >= a.z ? (v.y >= 0.0 ? 2 : 3) : (v.z >= 0.0 ? 4 : 5);
  vec2 c = vec2(dot(uShadowFaceS[f], v), dot(uShadowFaceT[f], v)) / dot(uShadowFaceM[f], v);
  ivec2 xy = clamp(ivec2(floor((c * 0.5 + 0.5) * float(uShadowSize))), ivec2(0), ivec2(uShadowSize - 1));
  return ivec3(xy, f);
}

// The direction (from the light, not normalized) through a texel's centre.
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

// The votes' verdict: the fraction open; undecided (gShadowUndecided) when
// they are mixed or p's texel `own` lies within SHADOW_RADIUS of the layer's
// edge.
float shadowVerdict(ivec2 own, int open, int count) {
  if (any(lessThan(own, ivec2(SHADOW_RADIUS))) || any(greaterThanEqual(own, ivec2(uShadowSize - SHADOW_RADIUS)))) {
    gShadowUndecided = true;
  }
  if (open != 0 && open != count) gShadowUndecided = true;
  return count == 0 ? 1.0 : float(open) / float(count);
}

// Whether the light reaches p (ng faces the light): 1 lit, 0 shadowed, by
// the map's texels within SHADOW_RADIUS of p's (3 x 3). Each texel's centre
// direction meets p's tangent plane at a distance from the light; a texel
// holding a nearer surface sees an occluder. All texels open: lit; all
// occluded: shadowed; a mix (a shadow edge, or a receiver curving towards
// the light), a direction grazing the plane or p within a texel of its
// face's edge: undecided (gShadowUndecided), and the fraction open.
float shadowVisibility(int light, vec3 p, vec3 ng) {
  if (uShadowLayer[light] < 0) return 1.0;
  vec3 v = p - uLightPosition[light];
  ivec3 own = shadowTexel(v);
  float plane = -dot(v, ng);  // the light's distance from p's tangent plane
  int open = 0, count = 0;
  float step = 2.0 / float(uShadowSize);
  vec3 s = step * uShadowFaceS[own.z], t = step * uShadowFaceT[own.z];
  vec3 centre = shadowTexelDirection(own.xy, own.z);
  for (int dy = -SHADOW_RADIUS; dy <= SHADOW_RADIUS; ++dy) {
    for (int dx = -SHADOW_RADIUS; dx <= SHADOW_RADIUS; ++dx) {
      ivec2 xy = clamp(own.xy + ivec2(dx, dy), ivec2(0), ivec2(uShadowSize - 1));
      vec2 d = vec2(xy - own.xy);
      shadowVote(light, ivec3(xy, own.z), centre + d.x * s + d.y * t, plane, ng, open, count);
    }
  }
  return shadowVerdict(own.xy, open, count);
}

#ifdef DIRECTIONAL_LIGHTS
// shadowVisibility for a directional light's orthographic layer: each of the
// SHADOW_RADIUS texels around p's votes with the line along the light
// through its centre, which meets p's tangent plane at a distance from the
// near plane; a texel holding a nearer surface sees an occluder.
float parallelVisibility(int light, vec3 p, vec3 ng) {
  if (uShadowLayer[light] < 0) return 1.0;
  vec3 m = uLightDirection[light], s = uShadowAxisS[light], t = uShadowAxisT[light];
  vec3 o = uShadowCentre - uShadowRadius * m;  // the centre of the layer's near plane
  float halfWidth = uShadowRadius;
  float cosine = -dot(m, ng);
  if (cosine < 0.01) {
    gShadowUndecided = true;
    return 1.0;
  }
  vec2 c = vec2(dot(p - o, s), dot(p - o, t)) / halfWidth;
  ivec2 own = clamp(ivec2(floor((c * 0.5 + 0.5) * float(uShadowSize))), ivec2(0), ivec2(uShadowSize - 1));
  float tolerance = uShadowFar[light] * 1e-4 * (1.0 + 1.0 / cosine);
  int open = 0, count = 0;
  for (int dy = -SHADOW_RADIUS; dy <= SHADOW_RADIUS; ++dy) {
    for (int dx = -SHADOW_RADIUS; dx <= SHADOW_RADIUS; ++dx) {
      ivec2 xy = clamp(own + ivec2(dx, dy), ivec2(0), ivec2(uShadowSize - 1));
      vec2 centre = ((vec2(xy) + 0.5) / float(uShadowSize) * 2.0 - 1.0) * halfWidth;
      vec3 base = o + centre.x * s + centre.y * t;
      float expected = dot(p - base, ng) / -cosine;
      float stored = texelFetch(uShadowMaps, ivec3(xy, uShadowLayer[light]), 0).r * uShadowFar[light];
      ++count;
      if (stored >= expected - tolerance) ++open;
    }
  }
  return shadowVerdict(own, open, count);
}
#endif
#endif

// Adds the diffuse and specular light of a point light of intensity lightI
// in direction l (unit, facing the surface), as the tracer's addPhong: the
// thesis's Phong, or with a field path transport's lobes.
void addPhong(inout vec3 result, vec3 lightI, vec3 c, vec3 ns, vec3 l, vec3 toViewer) {
#ifdef FIELD
  result += lobesReflect(lightI, gLobeAlbedo, gLobeSpecular, uTerms.w, ns, l, toViewer);
#else
  result += phongDiffuse(lightI, c, uTerms.y, ns, l);
#ifdef SPECULAR
  result += phongSpecular(lightI, uTerms.z, uTerms.w, ns, l, toViewer);
#endif
#endif
}

#ifdef LIT
// Whether light from l reaches the smooth surface from behind the flat
// triangle (a smooth mesh's terminator; the caller has checked ns). Whether
// the triangle's neighbours block it is the tracer's to decide, its shadow
// rays leaving from the point lifted onto that surface (Geometry::lifted):
// undecided wherever the tracer casts shadow rays. GL's estimate: unshadowed.
bool behindTriangle(vec3 l, vec3 ng) {
  if (dot(l, ng) > 0.0) return false;
  if (uSelfShadowing) gShadowUndecided = true;
  return true;
}
#endif

#ifdef FIELD
// Probe i's texel k (its coefficients' floats, then its map's moments).
vec4 fieldTexel(int i, int k) {
  return texelFetch(uField, ivec2((i % FIELD_PROBES_PER_ROW) * FIELD_PROBE_TEXELS + k, i / FIELD_PROBES_PER_ROW), 0);
}

// Probe i's irradiance toward n, from its coefficients four floats a texel.
vec3 probeIrradiance(int i, vec3 n) {
  vec4 t[FIELD_SH_TEXELS];
  for (int k = 0; k < FIELD_SH_TEXELS; ++k) t[k] = fieldTexel(i, k);
  vec3 c[9];
  c[0] = t[0].xyz;
  c[1] = vec3(t[0].w, t[1].xy);
  c[2] = vec3(t[1].zw, t[2].x);
  c[3] = t[2].yzw;
  c[4] = t[3].xyz;
  c[5] = vec3(t[3].w, t[4].xy);
  c[6] = vec3(t[4].zw, t[5].x);
  c[7] = t[5].yzw;
  c[8] = t[6].xyz;
  return shIrradiance(c, n);
}

// The field's irradiance at p toward unit n, its cell's eight probes blended
// as IrradianceField::irradiance blends them; gFieldUndecided where too
// little of their weight sees p, or too much is in doubt.
vec3 fieldIrradiance(vec3 p, vec3 n) {
  float minStep = min(uFieldStep.x, min(uFieldStep.y, uFieldStep.z));
  vec3 q = p + (0.25 * minStep) * n;
  vec3 at = clamp((q - uFieldOrigin) / uFieldStep, vec3(0.0), vec3(uFieldCounts - 1));
  ivec3 base = min(ivec3(at), uFieldCounts - 2);
  vec3 alpha = at - vec3(base);
  float minVariance = (0.05 * minStep) * (0.05 * minStep);
  vec3 sum = vec3(0.0);
  float weight = 0.0, share = 0.0, doubt = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    ivec3 offset = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    ivec3 cell = base + offset;
    int i = (cell.z * uFieldCounts.y + cell.y) * uFieldCounts.x + cell.x;
    vec3 toProbe = uFieldOrigin + vec3(cell) * uFieldStep - q;
    float d = length(toProbe);
    vec3 dir = d > 0.0 ? toProbe / d : n;
    vec3 t = mix(1.0 - alpha, alpha, vec3(offset));
    float s = probeShare(t.x * t.y * t.z, dir, n);
    ivec2 xy = clamp(ivec2(octahedralPoint(-dir) * float(FIELD_MAP_SIDE)), ivec2(0), ivec2(FIELD_MAP_SIDE - 1));
    float v = probeVisibility(fieldTexel(i, FIELD_SH_TEXELS + xy.y * FIELD_MAP_SIDE + xy.x).rg, d, minVariance);
    float w = s * v;
    sum += w * probeIrradiance(i, n);
    weight += w;
    share += s;
    if (visibilityInDoubt(v)) doubt += s;
  }
  if (!(share > 0.0 && weight >= FIELD_DECIDED_SHARE * share && doubt <= FIELD_DOUBT_SHARE * share)) {
    gFieldUndecided = true;
  }
  return weight > 0.0 ? sum / weight : vec3(0.0);
}

// The emitters' light at p toward unit n, unshadowed: each triangle's in
// closed form (where something may block it, the pixel is traced:
// client/raster/penumbra_proof.h).
vec3 emitterIrradiance(vec3 p, vec3 n) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < uEmitterCount; ++i) {
    sum += triangleIrradiance(uEmitters[4 * i + 3], uEmitters[4 * i], uEmitters[4 * i + 1], uEmitters[4 * i + 2], p, n);
  }
  return sum;
}

// The light other surfaces send p, as the tracer's fieldLight: the diffuse
// albedo over pi times the field's and the emitters' irradiance.
vec3 fieldLight(vec3 p, vec3 ns) {
  if (gLobeAlbedo == vec3(0.0)) return gLobeAlbedo;
  return gLobeAlbedo * ((fieldIrradiance(p, ns) + emitterIrradiance(p, ns)) * 0.318309886);
}
#endif

vec3 shade(vec3 p, vec3 ng, vec3 ns, vec2 uv) {
  vec3 c = surfaceColour(uv);
#if defined(LIT) || defined(FIELD)
  vec3 toViewer = normalize(uEye - p);
  if (dot(ng, toViewer) < 0.0) ng = -ng;
  float len = length(ns);
  ns = len > 0.0 ? ns / len : ng;
  if (dot(ns, ng) < 0.0) ns = -ns;
#endif
#ifdef FIELD
  gLobeAlbedo = diffuseAlbedo(c, uTerms.y, uTerms.z, uOtherLobes.x, uOtherLobes.y);
  gLobeSpecular = specularWeight(c, uTerms.y, uTerms.z, uOtherLobes.x, uOtherLobes.y);
  vec3 result = fieldLight(p, ns);
#else
  vec3 result = phongAmbient(c, uTerms.x);
#endif
#ifdef EMISSIVE
  result += emitted(uv);
#endif
#ifdef LIT
  for (int i = 0; i < uLightCount; ++i) {
#ifdef DIRECTIONAL_LIGHTS
    if (uLightKind[i] == LIGHT_DIRECTIONAL) {
      vec3 l = -uLightDirection[i];
      if (dot(l, ns) <= 0.0) continue;
      bool behind = behindTriangle(l, ng);
#ifdef SHADOWS
      float visible = behind ? 1.0 : parallelVisibility(i, p, ng);
      if (visible == 0.0) continue;
#else
      float visible = 1.0;
#endif
      addPhong(result, visible * uLightColor[i], c, ns, l, toViewer);
      continue;
    }
#endif
    vec3 toLight = uLightPosition[i] - p;
    float d = length(toLight);
    if (!(d > 0.0)) continue;
    vec3 l = toLight / d;
    if (dot(l, ns) <= 0.0) continue;
#ifdef SPOT_LIGHTS
    vec2 cone = uLightCone[i];
    float share = uLightKind[i] == LIGHT_SPOT ? spotFactor(uLightDirection[i], cone.x, cone.y, l) : 1.0;
    if (share == 0.0) continue;
#endif
    bool behind = behindTriangle(l, ng);
#ifdef SHADOWS
    float visible = behind ? 1.0 : shadowVisibility(i, p, ng);
    if (visible == 0.0) continue;
#else
    float visible = 1.0;
#endif
    vec3 lightI = attenuate(visible * uLightColor[i], uLightAttenuation[i], d);
#ifdef SPOT_LIGHTS
    if (uLightKind[i] == LIGHT_SPOT) lightI *= share;
#endif
    addPhong(result, lightI, c, ns, l, toViewer);
  }
  // Area and sphere lights unshadowed: where they may be blocked the pixel
  // is traced (client/raster/penumbra_proof.h).
  for (int i = 0; i < uAreaCount; ++i) {
    ivec2 at = ivec2(AREA_POINT_FIELDS * (i % AREA_POINTS_PER_ROW), i / AREA_POINTS_PER_ROW);
    vec3 position = texelFetch(uAreaPoints, at, 0).rgb;
    vec3 normal = texelFetch(uAreaPoints, at + ivec2(3, 0), 0).rgb;
    if (normal != vec3(0.0) && dot(p - position, normal) <= 0.0) continue;
    vec3 toLight = position - p;
    float d = length(toLight);
    if (!(d > 0.0)) continue;
    vec3 l = toLight / d;
    if (dot(l, ns) <= 0.0) continue;
    behindTriangle(l, ng);
    vec3 lightI = attenuate(texelFetch(uAreaPoints, at + ivec2(1, 0), 0).rgb,
                            texelFetch(uAreaPoints, at + ivec2(2, 0), 0).rgb, d);
    addPhong(result, lightI, c, ns, l, toViewer);
  }
#endif
  return result;
}
)";

const char* const kMeshVertexShader = R"(#version 330
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
layout(location = 3) in vec3 aFaceNormal;
layout(location = 4) in int aObject;
layout(location = 5) in vec3 aColor;  // read only by VERTEX_COLORS variants
uniform mat4 uViewProjection;
out vec3 vPosition;
out vec3 vNormal;
out vec2 vUv;
out vec3 vColor;
flat out vec3 vFaceNormal;
flat out int vObject;
void main() {
  vPosition = aPosition;
  vNormal = aNormal;
  vUv = aUv;
  vColor = aColor;
  vFaceNormal = aFaceNormal;
  vObject = aObject;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)";

const char* const kMeshFragmentShader = R"(
in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
flat in vec3 vFaceNormal;
flat in int vObject;
void main() {
#ifdef DEPTH_MAP
  gl_FragDepth = (uDepthAxis != vec3(0.0) ? dot(vPosition - uEye, uDepthAxis) : length(vPosition - uEye)) / uFar;
#endif
#ifdef TRACED
  fragColor = vec4(0.0, 0.0, 0.0, 1.0);
  fragSurface = uint(vObject) << 2 | 1u;
#else
  fragColor = vec4(encodeOutput(shade(vPosition, vFaceNormal, vNormal, vUv)), 1.0);
  fragSurface = surfaceOf(vObject);
#endif
}
)";

// Spheres are exact on screen: each sphere's bounding box is drawn and each
// fragment casts the eye ray through it against the sphere (the tracer's
// formula), writing the hit's depth as OpenGL would a mesh's; front and
// back faces of the box give the same hit, so the camera may also be inside
// the box (the box's far faces are then drawn, its near ones otherwise).
const char* const kSphereVertexShader = R"(#version 330
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aSphere;  // centre, radius
layout(location = 2) in int aObject;
uniform mat4 uViewProjection;
out vec3 vPosition;
flat out vec4 vSphere;
flat out int vObject;
void main() {
  vPosition = aPosition;
  vSphere = aSphere;
  vObject = aObject;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)";

const char* const kSphereFragmentShader = R"(
uniform mat4 uViewProjection;
in vec3 vPosition;
flat in vec4 vSphere;
flat in int vObject;
void main() {
  // The ray through the fragment: from the eye, or in a directional light's
  // map along its axis from its near plane.
#ifdef DEPTH_MAP
  bool parallel = uDepthAxis != vec3(0.0);
  vec3 d = parallel ? uDepthAxis : normalize(vPosition - uEye);
  vec3 origin = parallel ? vPosition - dot(vPosition - uEye, uDepthAxis) * uDepthAxis : uEye;
#else
  vec3 d = normalize(vPosition - uEye);
  vec3 origin = uEye;
#endif
  vec3 f = origin - vSphere.xyz;
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
  vec3 p = origin + t * d;
  vec3 n = normalize(p - vSphere.xyz);
  p = vSphere.xyz + vSphere.w * n;
#ifdef DEPTH_MAP
  gl_FragDepth = (parallel ? dot(p - uEye, uDepthAxis) : length(p - uEye)) / uFar;
#else
  vec4 clip = uViewProjection * vec4(p, 1.0);
  gl_FragDepth = clip.z / clip.w;
#endif
#ifdef TRACED
  fragColor = vec4(0.0, 0.0, 0.0, 1.0);
  fragSurface = uint(vObject) << 2 | 1u;
#else
  float u = atan(n.x, n.z) / (2.0 * 3.14159265);
  float v = acos(clamp(-n.y, -1.0, 1.0)) / 3.14159265;
  vec2 uv = vec2(u < 0.0 ? u + 1.0 : u, v);
  fragColor = vec4(encodeOutput(shade(p, n, n, uv)), 1.0);
  fragSurface = surfaceOf(vObject);
#endif
}
)";

}  // namespace glint::gl
