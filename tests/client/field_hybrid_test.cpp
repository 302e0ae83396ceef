// The hybrid frame under path transport: OpenGL draws the irradiance
// field's light as the tracer reads it (Tracer::fieldLight), the emitters'
// penumbra and the pixels the field cannot decide are traced, and the
// traced pixels are the tracer's own.
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "client/raster/hybrid_frame.h"
#include "client/raster/offscreen_context.h"
#include "client/raster/pixel_mark.h"
#include "client/raster/raster_scene.h"
#include "common/base/thread_pool.h"
#include "common/render/field_probes.h"
#include "common/render/frame.h"
#include "common/render/prepared_scene.h"
#include "common/scene/camera.h"
#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using json = nlohmann::json;

// A frame of the scene with one ray through each pixel's centre (as
// OpenGL's one sample a pixel).
FrameSettings centreRays(const Scene& scene, int width, int height) {
  FrameSettings frame = scene.frame;
  frame.width = width;
  frame.height = height;
  frame.sampling.pattern = SamplePattern::kRegular;
  frame.sampling.samples = 1;
  return frame;
}

MaskSettings autoRule() {
  MaskSettings mask;
  mask.rule = MaskRule::kAuto;
  return mask;
}

struct FieldHybrid {
  HybridResult hybrid;
  FrameImage traced;  // the whole frame by the tracer that reads the field
  FrameImage direct;  // the same with direct light (max depth 1)
};

FieldHybrid renderBoth(const PreparedScene& prepared, const FrameSettings& frame, const IrradianceField& field) {
  ThreadPool pool(2);
  LocalTileService service(prepared, pool, &field);
  gl::OffscreenContext context(frame.width, frame.height);
  gl::RasterScene raster(context.api(), prepared.scene());
  raster.useField(field);
  FieldHybrid out;
  renderHybrid(context.api(), raster, service, frame, autoRule(), 16, out.hybrid);
  out.traced = renderFrame(service, frame, {}).image;
  FrameSettings direct = frame;
  direct.tracing.maxDepth = 1;
  out.direct = renderFrame(service, direct, {}).image;
  return out;
}

// The Cornell box at one ray a pixel: every pixel OpenGL draws is the
// tracer's within 2/255 (the field's light, the emitter's unshadowed light
// where its penumbra proof holds); every traced pixel is the tracer's own.
TEST(FieldHybrid, RasterPixelsAreTheTracersAndTracedPixelsItsOwn) {
  Scene scene = loadSceneFile(test::sourcePath("scenes/cornell.json"));
  const FrameSettings frame = centreRays(scene, 96, 96);
  const PreparedScene prepared(std::move(scene), BvhSettings{});
  RayStats stats;
  const IrradianceField field = buildField(prepared, frame, {8, 256}, stats);
  const FieldHybrid both = renderBoth(prepared, frame, field);
  const HybridResult& h = both.hybrid;
  int raster = 0, worst = 0, tracedUnlike = 0;
  for (std::size_t i = 0; i < h.mask.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const int here = h.image.rgb[3 * i + k];
      if (h.mask[i] == kRasterPixel) {
        worst = std::max(worst, std::abs(here - both.traced.rgb[3 * i + k]));
      } else {
        const FrameImage& expected = tracedWithDirectLight(h.mask[i]) ? both.direct : both.traced;
        tracedUnlike += here != expected.rgb[3 * i + k] ? 1 : 0;
      }
    }
    raster += h.mask[i] == kRasterPixel ? 1 : 0;
  }
  std::printf("cornell 96 x 96: %d raster pixels, %zu traced (%zu for the emitter's penumbra or the field), worst %d/255\n",
              raster, h.maskedPixels, h.shadowEdgePixels, worst);
  EXPECT_GT(raster, 96 * 96 / 4);  // OpenGL draws a good share
  EXPECT_GT(h.shadowEdgePixels, 0u);  // the boxes' shadows are traced
  EXPECT_LE(worst, 2);
  EXPECT_EQ(tracedUnlike, 0);
}

// Two rooms side by side, a thin wall between them, the left one lit by its
// glowing far wall; the camera stands in the right one. No visible light of
// the left room reaches the right room's pixels that OpenGL draws: the
// field's visibility keeps it out, or the pixel is marked and traced.
TEST(FieldHybrid, NoLightLeaksThroughAThinWallIntoRasterPixels) {
  json objects = json::array();
  const auto quad = [&](std::vector<std::vector<double>> c, const char* m) {
    objects.push_back({{"type", "quad"}, {"corners", c}, {"material", m}});
  };
  quad({{0, 0, 0}, {4, 0, 0}, {4, 0, 2}, {0, 0, 2}}, "wall");  // floor
  quad({{0, 2, 0}, {0, 2, 2}, {4, 2, 2}, {4, 2, 0}}, "wall");  // ceiling
  quad({{0, 0, 0}, {0, 2, 0}, {4, 2, 0}, {4, 0, 0}}, "wall");  // back
  quad({{0, 0, 2}, {4, 0, 2}, {4, 2, 2}, {0, 2, 2}}, "wall");  // front
  quad({{0, 0, 0}, {0, 0, 2}, {0, 2, 2}, {0, 2, 0}}, "glow");  // the left room's far wall
  quad({{4, 0, 0}, {4, 2, 0}, {4, 2, 2}, {4, 0, 2}}, "wall");  // the right room's far wall
  quad({{2, 0, 0}, {2, 2, 0}, {2, 2, 2}, {2, 0, 2}}, "wall");  // between them
  const json scene = {
      {"glint", 1},
      {"image", {{"width", 64}, {"height", 48}}},
      {"camera", {{"eye", {3.8, 1.6, 1.0}}, {"look_at", {2.0, 0.6, 1.0}}, {"fov_y", 80}}},
      {"tracing", {{"transport", "path"}, {"max_bounces", 4}}},
      {"materials",
       {{"wall", {{"color", {1, 1, 1}}, {"diffuse", 0.5}}},
        {"glow", {{"color", {1, 1, 1}}, {"diffuse", 0.5}, {"emission", {4, 4, 4}}}}}},
      {"objects", objects}};
  const PreparedScene prepared(test::sceneFromJson(scene.dump()), BvhSettings{});
  const FrameSettings frame = centreRays(prepared.scene(), 64, 48);
  RayStats stats;
  const IrradianceField field = buildField(prepared, frame, {8, 256}, stats);
  const FieldHybrid both = renderBoth(prepared, frame, field);
  const HybridResult& h = both.hybrid;
  // A pixel's ray through its centre meets the dark room or the wall's face
  // in it (not the lit room's walls, which a ray grazing the wall's corners
  // may reach).
  const Camera camera(frame.camera, frame.width, frame.height);
  const auto inDarkRoom = [&](std::size_t i) {
    const Ray ray = camera.generateRay({float(i % 64) + 0.5f, float(i / 64) + 0.5f});
    const std::optional<Hit> hit = prepared.bvh().intersect(ray, 1e30f);
    return hit && (ray.o + hit->t * ray.d).x >= 2.0f;
  };
  int raster = 0, brightest = 0;
  for (std::size_t i = 0; i < h.mask.size(); ++i) {
    if (h.mask[i] != kRasterPixel || !inDarkRoom(i)) continue;
    ++raster;
    for (int k = 0; k < 3; ++k) brightest = std::max(brightest, int(h.image.rgb[3 * i + k]));
  }
  std::printf("dark room 64 x 48: %d raster pixels, %zu traced, brightest raster byte %d\n", raster,
              h.maskedPixels, brightest);
  // At most one step of 255 (sRGB: a linear 3e-4, under 1/1000 of the lit
  // room's): a probe across the wall whose coarse map blurs the wall into
  // its neighbours keeps a weight that small without falling in doubt.
  EXPECT_GT(raster, 64 * 48 / 10);
  EXPECT_LE(brightest, 1);
}

}  // namespace
}  // namespace glint
