#include "common/base/build_identity.h"

#include <cstdint>
#include <cstdio>

namespace glint {
namespace {

// Raised whenever a change to the tracer, the shading or the sampling
// changes the bytes of any pixel.
// 2: the adaptive pattern; 3: power() (common/math/power.h); 4: exponential()
// and sineCosine() (common/math/power.h, common/math/circular.h); 5: the hybrid frame
// rasterizes at one sample a pixel and traces its edges
// (client/raster/raster_edges.h); 6: the raster reads the shadow maps only where
// the geometry does not prove the light reaches (client/raster/light_proof.h), and
// tests OpenGL's own depth; 7: a material's colour multiplies its texture
// (glTF's baseColorFactor; the scenes' own pixels are unchanged); 8: a
// material's emission (glTF's emissiveFactor x emissiveTexture, MTL's Ke),
// glTF's KHR_texture_transform and a mesh's vertex colours; 9: sRGB is the
// 8-bit encoding of a scene that names none (the scenes in scenes/ name
// linear and keep their bytes); 10: image textures' wrap modes, and glTF
// samplers' wrap modes and magnification filter; 11: the shadow terminator
// (shadow rays from the smooth surface); 12: path transport (a scene that
// asks for it renders otherwise than a build without it would; Whitted
// pixels unchanged); 13: path transport draws its choices from scrambled
// Sobol points (Whitted pixels unchanged); 14: path transport's diffuse
// bounce weighs by the albedo exactly, turns its azimuth in float and draws
// a lobe only where there is a choice (Whitted pixels unchanged); 15: a
// frame that reads an irradiance field lights by path transport's lobes
// (lobesReflect), the tracer confirms the field's probes with rays, and a
// probe about hidden carries no weight (frames without a field unchanged);
// 16: a frame that reads an irradiance field takes an emitting triangle's
// unshadowed light in closed form (triangleIrradiance) where it summed the
// triangle's fixed points (frames without a field unchanged).
constexpr int kTracerVersion = 16;

// FNV-1a: the flags only need a short, stable fingerprint.
std::uint64_t fingerprint(const char* text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char* c = text; *c; ++c) h = (h ^ static_cast<unsigned char>(*c)) * 1099511628211ull;
  return h;
}

}  // namespace

const std::string& buildIdentity() {
  static const std::string identity = [] {
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fingerprint(GLINT_PIXEL_FLAGS)));
    return "pixels-" + std::to_string(kTracerVersion) + " " + GLINT_COMPILER + " " + hash;
  }();
  return identity;
}

}  // namespace glint
