#pragma once

#include <string>

namespace glint::gl {

// GLSL sources of the raster pass. The fragment shaders compute exactly the
// tracer's direct lighting (common/shading.cpp, common/tracer.cpp Tracer::shade
// without shadow rays): the same terms, face-forwarded normals, attenuation,
// checker index and image lookups (common/texture.cpp).
// Fragment shaders are fragmentPrelude(), kFragmentShading and their own main().
std::string fragmentPrelude();  // #version and the array sizes below, as GLSL defines
extern const char* const kFragmentShading;
extern const char* const kMeshVertexShader;
extern const char* const kMeshFragmentShader;
extern const char* const kSphereVertexShader;
extern const char* const kSphereFragmentShader;

// Limits of the uniform arrays the shaders declare (defined only here).
constexpr int kMaxLights = 16;
constexpr int kMaxMaterials = 128;
constexpr int kMaxTextures = 32;

}  // namespace glint::gl
