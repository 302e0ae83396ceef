#include "tests/common/test_support.h"

#include "common/file_source.h"
#include "common/renderer.h"
#include "common/scene_load.h"
#include "common/thread_pool.h"

namespace glint::test {

Scene sceneFromJson(const std::string& json) {
  MemorySource files;
  return loadScene(json, files);
}

FrameResult render(const Scene& scene, int threads, int tileSize) {
  return render(scene, EffectPlan::derive(scene), threads, tileSize);
}

FrameResult render(const Scene& scene, const EffectPlan& plan, int threads, int tileSize) {
  const Renderer renderer(scene, BvhSettings{}, plan);
  ThreadPool pool(threads);
  FrameOptions options;
  options.tileSize = tileSize;
  return renderFrame(renderer, pool, options);
}

std::string sourcePath(const std::string& relative) { return std::string(GLINT_SOURCE_DIR) + "/" + relative; }

Rgb pixelAt(const FrameImage& image, int x, int y) {
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                         static_cast<std::size_t>(x)) * 3;
  return {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
}

}  // namespace glint::test
