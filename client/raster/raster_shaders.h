#pragma once

#include <string>

namespace glint::gl {

// GLSL sources of the raster pass. The fragment shaders compute exactly the
// tracer's direct lighting (common/scene/shading.glsl's functions, which they
// compile too; common/render/tracer.cpp Tracer::shade;
// shadow rays answered by the shadow maps where they can decide, see
// client/raster/shadow_maps.h): the same terms, face-forwarded normals, attenuation,
// checker index and image lookups (common/scene/texture.cpp).
//
// Each material is drawn by a program made for what it needs (a variant):
// llvmpipe runs both sides of every branch of a fragment shader, so a term a
// material does not have (a texture, the specular lobe, the shadow maps)
// costs nothing only when it is compiled out. The material's own values are
// uniforms set per draw call, so the number of materials and textures is
// bounded by memory alone.
enum class TextureKind { kNone, kChecker, kNearest, kBilinear };
struct ShaderVariant {
  bool sphere = false;
  bool traced = false;  // a masked material: depth and surface only, no shading
  TextureKind texture = TextureKind::kNone;
  bool emits = false;                         // the material's emission is added
  TextureKind emission = TextureKind::kNone;  // its emission texture: none or an image
  bool vertexColors = false;                  // a mesh's colours multiply the surface colour
  bool lit = false;       // diffuse or specular terms (else ambient alone)
  bool specular = false;
  bool shadows = false;   // the shadow maps are read
  bool srgb = false;      // the 8-bit encoding (else linear)
  bool spotLights = false;         // the scene has spot lights: their cones are applied
  bool directionalLights = false;  // it has directional lights
  bool field = false;  // path transport's light from the irradiance field (client/raster/field_light.h), not ambient
  // Drawn into a shadow map: writes the distance from the eye / far, which
  // the maps hold. The frame's own depth is the projection's (reversed: 1 at
  // the near plane, falling as 1 / distance), so that OpenGL tests it before
  // shading a mesh's fragment.
  bool depthMap = false;

  int key() const;
  // The #defines that select the variant in the sources below.
  std::string defines() const;
};

// Every fragment shader is fragmentPrelude(variant) (the defines, then the
// tracer's own shading terms, common/scene/shading.glsl), kFragmentShading
// and its own main(); it writes the colour (location 0) and the surface value
// `object << kPixelMarkBits | mark` (location 1, client/raster/pixel_mark.h).
std::string fragmentPrelude(const ShaderVariant& variant);
extern const char* const kFragmentShading;
extern const char* const kMeshVertexShader;
extern const char* const kMeshFragmentShader;
extern const char* const kSphereVertexShader;
extern const char* const kSphereFragmentShader;

// The length of the shaders' light arrays (defined only here; MAX_LIGHTS).
constexpr int kMaxLights = 16;
// Area lights' points and sphere lights' centres are a float texture, not
// uniform arrays, so that their number is bounded by memory alone: 4 texels
// a point (kAreaPointFields: position, colour, attenuation, normal), this
// many points a row (AREA_POINTS_PER_ROW).
constexpr int kAreaPointFields = 4;
constexpr int kAreaPointsPerRow = 1024;
// Texels on each side of a point's own that its shadow test reads (1: 3 x 3;
// the shaders' SHADOW_RADIUS).
constexpr int kShadowRadius = 1;

}  // namespace glint::gl
