#pragma once

#include <string>

#include "common/base/file_source.h"
#include "common/scene/load_limits.h"

namespace glint::fuzz {

// Limits small enough that a run never waits on a huge allocation: what the
// loaders' fuzz targets load under.
inline LoadLimits smallLimits() {
  LoadLimits limits;
  limits.maxSceneBytes = std::size_t{64} << 20;
  limits.maxTexturePixels = std::size_t{1} << 20;
  limits.maxTriangles = limits.maxVertices = 1'000'000;
  return limits;
}

// A 1x1 24-bit BMP (green): a texture small enough for every run.
inline std::string tinyBmp() {
  const unsigned char bmp[] = {'B', 'M', 58, 0, 0, 0, 0, 0, 0, 0, 54, 0, 0, 0, 40, 0, 0, 0, 1, 0, 0, 0, 1, 0,
                               0, 0, 1, 0, 24, 0, 0, 0, 0, 0, 4, 0, 0, 0, 0x13, 0x0b, 0, 0, 0x13, 0x0b, 0,
                               0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 255, 0, 0};
  return std::string(reinterpret_cast<const char*>(bmp), sizeof bmp);
}

// A 2x1 Radiance HDR (a blue and a bright white texel): an environment
// image small enough for every run.
inline std::string tinyHdr() {
  const unsigned char texels[] = {64, 96, 160, 128, 200, 200, 200, 133};
  return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n" +
         std::string(reinterpret_cast<const char*>(texels), sizeof texels);
}

inline const char* kCubeObj =
    "mtllib cube.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "usemtl red\nf 1/1 2/2 3/3\nusemtl blue\nf 1/1 3/3 4/4\n";
inline const char* kCubeMtl =
    "newmtl red\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 40\nd 0.5\nNi 1.3\nnewmtl blue\nKd 0 0 1\nmap_Kd tex.bmp\n";

// The files a fuzzed scene may name: a textured OBJ with its MTL, the
// texture, an environment image (scenes/'s sky.hdr) and a small stand-in for scenes/'s bunny (the real one is 220 KB,
// too slow to parse on every run).
inline void addFuzzFiles(MemorySource& files) {
  files.add("models/cube.obj", kCubeObj);
  files.add("models/cube.mtl", kCubeMtl);
  files.add("models/tex.bmp", tinyBmp());
  files.add("sky.hdr", tinyHdr());
  files.add("models/bunny.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n");
}

}  // namespace glint::fuzz
