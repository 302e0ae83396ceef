#pragma once

#include <filesystem>
#include <string>

#include "common/render/effects.h"
#include "common/render/frame.h"
#include "common/image/linear_image.h"
#include "common/render/ray_stats.h"
#include "common/geometry/geometry.h"
#include "common/scene/scene.h"

namespace glint::test {

// Loads a scene from JSON text that names no files.
Scene sceneFromJson(const std::string& json);

// Every effect switched on for every material and light: the reference the
// tests compare EffectPlan::derive against.
EffectPlan everyEffect(const Scene& scene);

// Direct light only, no shadow, reflected or refracted rays: what the OpenGL
// pass draws, for comparing the two.
EffectPlan directLightOnly(const Scene& scene, const FrameSettings& frame);

// Renders a whole frame through the tile interface.
FrameResult render(const Scene& scene, int threads = 1, int tileSize = 32);
FrameResult render(const Scene& scene, const EffectPlan& plan, int threads = 1, int tileSize = 32);

// Renders a whole frame's linear colour (before 8-bit rounding, not
// clamped), its rays counted into `stats`.
LinearImage renderLinearFrame(const Scene& scene, RayStats& stats, int threads = 2, int tileSize = 16);
LinearImage renderLinearFrame(const Scene& scene, int threads = 2, int tileSize = 16);

// Path of a file in the source tree (scenes/room.json).
std::string sourcePath(const std::string& relative);

// A 24-bit BMP file of width x height pixels (all black); with `pixels`
// false, only its 54-byte header.
std::string bmp(int width, int height, bool pixels);

// A file in the temporary folder named for this process (ctest runs tests
// as processes side by side, so a fixed name would be shared).
std::filesystem::path scratchPath(const std::string& name);

// The bytes of a PNG of one colour: small to send, large once decoded.
std::string flatPng(int width, int height);
// A PNG file's bytes holding `image`.
std::string pngBytes(const FrameImage& image);

// RGB of pixel (x, y) of an image.
struct Rgb {
  int r, g, b;
};
Rgb pixelAt(const FrameImage& image, int x, int y);

}  // namespace glint::test

namespace glint::test {

// A closed triangle mesh of a sphere: an icosahedron subdivided `levels`
// times, vertices shared, wound counter-clockwise seen from outside.
MeshInput icosphere(int levels, const glm::vec3& centre, float radius);

}  // namespace glint::test
