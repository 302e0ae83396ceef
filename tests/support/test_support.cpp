#include "tests/support/test_support.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include <unistd.h>

#include <glm/geometric.hpp>

#include "common/base/file_source.h"
#include "common/image/image_write.h"
#include "common/render/linear_frame.h"
#include "common/render/prepared_scene.h"
#include "common/render/renderer.h"
#include "common/scene/scene_load.h"
#include "common/base/thread_pool.h"

namespace glint::test {

Scene sceneFromJson(const std::string& json) {
  MemorySource files;
  return loadScene(json, files);
}

FrameResult render(const Scene& scene, int threads, int tileSize) {
  return render(scene, EffectPlan::derive(scene), threads, tileSize);
}

FrameResult render(const Scene& scene, const EffectPlan& plan, int threads, int tileSize) {
  const PreparedScene prepared(scene, BvhSettings{});
  const Renderer renderer(prepared, scene.frame, plan);
  ThreadPool pool(threads);
  FrameOptions options;
  options.tileSize = tileSize;
  return renderFrame(renderer, pool, options);
}

LinearImage renderLinearFrame(const Scene& scene, RayStats& stats, int threads, int tileSize) {
  const PreparedScene prepared(scene, BvhSettings{});
  const Renderer renderer(prepared, scene.frame);
  ThreadPool pool(threads);
  FrameOptions options;
  options.tileSize = tileSize;
  return renderLinear(renderer, pool, stats, LinearRange::kUnbounded, options);
}

LinearImage renderLinearFrame(const Scene& scene, int threads, int tileSize) {
  RayStats stats;
  return renderLinearFrame(scene, stats, threads, tileSize);
}

EffectPlan everyEffect(const Scene& scene) {
  EffectPlan plan;
  plan.shadows = plan.reflection = plan.refraction = true;
  plan.textures = plan.emission = plan.vertexColors = plan.attenuation = plan.antialiasing = true;
  plan.environment = true;
  plan.materials.assign(scene.materials.size(), MaterialEffects{.direct = true,
                                                                .specular = true,
                                                                .textured = true,
                                                                .emits = true,
                                                                .reflects = true,
                                                                .refracts = true});
  plan.lights.assign(scene.lights.size(), true);
  return plan;
}

EffectPlan directLightOnly(const Scene& scene, const FrameSettings& frame) {
  EffectPlan plan = EffectPlan::derive(scene, frame);
  plan.shadows = plan.reflection = plan.refraction = false;
  for (MaterialEffects& e : plan.materials) e.reflects = e.refracts = false;
  return plan;
}

std::string sourcePath(const std::string& relative) {
  return (std::filesystem::path(GLINT_SOURCE_DIR) / relative).string();
}

Rgb pixelAt(const FrameImage& image, int x, int y) {
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                         static_cast<std::size_t>(x)) * 3;
  return {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
}

}  // namespace glint::test

namespace glint::test {

MeshInput icosphere(int levels, const glm::vec3& centre, float radius) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::uint32_t> f = {0, 11, 5, 0, 5,  1,  0,  1, 7, 0,  7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                                  4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9,  4,  3, 4,  2,  3, 2, 6, 3,
                                  6, 8, 3,  8,  9,  4, 9, 5, 2, 4, 11, 6, 2,  10, 8, 6,  7, 9, 8, 1};
  for (glm::vec3& p : v) p = glm::normalize(p);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    const auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoints.find(key);
      if (it != midpoints.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[b]));
      const auto index = static_cast<std::uint32_t>(v.size() - 1);
      midpoints[key] = index;
      return index;
    };
    std::vector<std::uint32_t> next;
    for (std::size_t i = 0; i < f.size(); i += 3) {
      const std::uint32_t a = f[i], b = f[i + 1], c = f[i + 2];
      const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    f = std::move(next);
  }
  MeshInput mesh;
  for (const glm::vec3& p : v) mesh.positions.push_back(centre + radius * p);
  mesh.indices = std::move(f);
  return mesh;
}

std::filesystem::path scratchPath(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("glint-" + std::to_string(::getpid()) + "-" + name);
}

std::string flatPng(int width, int height) {
  FrameImage image;
  image.width = width;
  image.height = height;
  image.rgb.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3, 200);
  return pngBytes(image);
}

std::string pngBytes(const FrameImage& image) {
  const std::filesystem::path path = scratchPath("image.png");
  writePng(path, image, Encoding::kSrgb);
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove(path);
  return bytes;
}

std::string bmp(int width, int height, bool pixels) {
  const std::size_t rowBytes = (static_cast<std::size_t>(width) * 3 + 3) / 4 * 4;
  const std::size_t dataBytes = rowBytes * static_cast<std::size_t>(height);
  std::string out(54 + (pixels ? dataBytes : 0), '\0');
  const auto put32 = [&out](std::size_t at, std::size_t v) {
    for (int i = 0; i < 4; ++i) out[at + static_cast<std::size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xff);
  };
  out[0] = 'B';
  out[1] = 'M';
  put32(2, 54 + dataBytes);
  put32(10, 54);
  put32(14, 40);
  put32(18, static_cast<std::size_t>(width));
  put32(22, static_cast<std::size_t>(height));
  out[26] = 1;
  out[28] = 24;
  return out;
}

}  // namespace glint::test
