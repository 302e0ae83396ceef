#pragma once

#include <string>

namespace glint::gl {

// GLSL sources of the raster pass. The fragment shaders compute exactly the
// tracer's direct lighting (common/shading.cpp, common/tracer.cpp Tracer::shade;
// shadow rays answered by the shadow maps where they can decide, see
// client/shadow_maps.h): the same terms, face-forwarded normals, attenuation,
// checker index and image lookups (common/texture.cpp).
// Fragment shaders are fragmentPrelude(), kFragmentShading and their own main(),
// in three variants (RasterScene::Shading): as they are, the colour and the
// marks; with MARKS_ONLY defined, the marks and a black colour (the
// anti-aliased pass draws the colour); with TRACED, neither (masked objects).
// With stencilExport (ARB_shader_stencil_export) a fragment whose shadow the
// maps cannot decide writes the stencil uUndecidedStencil.
std::string fragmentPrelude(bool stencilExport);  // #version, extensions and the limits below as GLSL defines
extern const char* const kFragmentShading;
extern const char* const kMeshVertexShader;
extern const char* const kMeshFragmentShader;
extern const char* const kSphereVertexShader;
extern const char* const kSphereFragmentShader;

// Limits of the uniform arrays the shaders declare (defined only here).
constexpr int kMaxLights = 16;
constexpr int kMaxMaterials = 128;
constexpr int kMaxTextures = 32;
// Texels on each side of a point's own that its shadow test reads (1: 3 x 3)
// where it decides the mask; the anti-aliased pass reads the point's own
// texel alone (a pixel it decided has the same answer there, and one it did
// not is traced).
constexpr int kShadowRadius = 1;

}  // namespace glint::gl
