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
#include "common/render/tile_service.h"
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

// A quad of the scene format.
json quad(std::vector<std::vector<double>> corners, const char* material) {
  return {{"type", "quad"}, {"corners", std::move(corners)}, {"material", material}};
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
  objects.push_back(quad({{0, 0, 0}, {4, 0, 0}, {4, 0, 2}, {0, 0, 2}}, "wall"));  // floor
  objects.push_back(quad({{0, 2, 0}, {0, 2, 2}, {4, 2, 2}, {4, 2, 0}}, "wall"));  // ceiling
  objects.push_back(quad({{0, 0, 0}, {0, 2, 0}, {4, 2, 0}, {4, 0, 0}}, "wall"));  // back
  objects.push_back(quad({{0, 0, 2}, {4, 0, 2}, {4, 2, 2}, {0, 2, 2}}, "wall"));  // front
  objects.push_back(quad({{0, 0, 0}, {0, 0, 2}, {0, 2, 2}, {0, 2, 0}}, "glow"));  // the left room's far wall
  objects.push_back(quad({{4, 0, 0}, {4, 2, 0}, {4, 2, 2}, {4, 0, 2}}, "wall"));  // the right room's far wall
  objects.push_back(quad({{2, 0, 0}, {2, 2, 0}, {2, 2, 2}, {2, 0, 2}}, "wall"));  // between them
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

// A clay sphere with a highlight under a point light, nothing else: the
// light between surfaces is about nil, so the field's frame is direct light
// alone, and OpenGL's pixels and the tracer's must both be path transport's
// (the diffuse and normalised Phong lobes), or the highlight is cut where
// the mask changes.
TEST(FieldHybrid, DirectLightIsPathTransportsLobesWhoeverDrawsIt) {
  const json scene = {
      {"glint", 1},
      {"image", {{"width", 64}, {"height", 64}}},
      {"camera", {{"eye", {0, 0.4, -3}}, {"look_at", {0, 0, 0}}, {"fov_y", 45}}},
      {"tracing", {{"transport", "path"}, {"max_bounces", 2}}},
      {"materials",
       {{"clay", {{"color", {0.8, 0.35, 0.25}}, {"diffuse", 0.8}, {"specular", 0.2}, {"shininess", 30}}}}},
      {"lights", {{{"type", "point"}, {"position", {2, 4, -3}}, {"color", {1, 1, 1}}}}},
      {"objects", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "clay"}}}}};
  const PreparedScene prepared(test::sceneFromJson(scene.dump()), BvhSettings{});
  const FrameSettings frame = centreRays(prepared.scene(), 64, 64);
  RayStats stats;
  const IrradianceField field = buildField(prepared, frame, {4, 64}, stats);
  const FieldHybrid both = renderBoth(prepared, frame, field);
  ThreadPool pool(2);
  LocalTileService pathOnly(prepared, pool);
  const FrameImage path = renderFrame(pathOnly, frame, {}).image;
  const HybridResult& h = both.hybrid;
  int raster = 0, worstRaster = 0, worstTraced = 0;
  for (std::size_t i = 0; i < h.mask.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const int apart = std::abs(int(h.image.rgb[3 * i + k]) - int(path.rgb[3 * i + k]));
      int& worst = h.mask[i] == kRasterPixel ? worstRaster : worstTraced;
      worst = std::max(worst, apart);
    }
    raster += h.mask[i] == kRasterPixel ? 1 : 0;
  }
  std::printf("clay sphere 64 x 64: %d raster pixels, worst apart from the path trace: raster %d/255, traced %d/255\n",
              raster, worstRaster, worstTraced);
  EXPECT_GT(raster, 64 * 64 / 4);
  EXPECT_LE(worstRaster, 3);
  EXPECT_LE(worstTraced, 3);
}

// Two rooms, one quad between them, a lamp in the right one and the camera
// in the left: where the tracer reads the field (the pixels it traces), the
// probes across the wall, whose coarse maps cannot tell, are confirmed by
// rays and carry nothing, at the coarsest settings as at fine ones.
TEST(FieldHybrid, TheTracerReadsNoLightThroughAThinWall) {
  json objects = json::array();
  objects.push_back(quad({{-2, 0, -1}, {2, 0, -1}, {2, 0, 1}, {-2, 0, 1}}, "w"));
  objects.push_back(quad({{-2, 2, -1}, {-2, 2, 1}, {2, 2, 1}, {2, 2, -1}}, "w"));
  objects.push_back(quad({{-2, 0, 1}, {2, 0, 1}, {2, 2, 1}, {-2, 2, 1}}, "w"));
  objects.push_back(quad({{-2, 0, -1}, {-2, 2, -1}, {2, 2, -1}, {2, 0, -1}}, "w"));
  objects.push_back(quad({{-2, 0, -1}, {-2, 0, 1}, {-2, 2, 1}, {-2, 2, -1}}, "w"));
  objects.push_back(quad({{2, 0, -1}, {2, 2, -1}, {2, 2, 1}, {2, 0, 1}}, "w"));
  objects.push_back(quad({{0, 0, -1}, {0, 2, -1}, {0, 2, 1}, {0, 0, 1}}, "w"));  // the wall between
  objects.push_back(quad({{0.8, 1.99, -0.3}, {0.8, 1.99, 0.3}, {1.4, 1.99, 0.3}, {1.4, 1.99, -0.3}}, "lamp"));
  const json scene = {
      {"glint", 1},
      {"image", {{"width", 64}, {"height", 48}}},
      {"camera", {{"eye", {-1.5, 1, -0.9}}, {"look_at", {-0.05, 0.8, 0.5}}, {"fov_y", 70}}},
      {"tracing", {{"transport", "path"}, {"max_bounces", 6}}},
      {"materials",
       {{"w", {{"color", {0.8, 0.8, 0.8}}, {"diffuse", 1}}},
        {"lamp", {{"color", {0.8, 0.8, 0.8}}, {"diffuse", 1}, {"emission", {20, 20, 20}}}}}},
      {"objects", objects}};
  const PreparedScene prepared(test::sceneFromJson(scene.dump()), BvhSettings{});
  const FrameSettings frame = centreRays(prepared.scene(), 64, 48);
  const Camera camera(frame.camera, frame.width, frame.height);
  for (const FieldSettings settings : {FieldSettings{FieldSettings::kMinProbes, FieldSettings::kMinRays},
                                       FieldSettings{4, 64}, FieldSettings{8, 256}, FieldSettings{16, 256}}) {
    RayStats stats;
    const IrradianceField field = buildField(prepared, frame, settings, stats);
    int points = 0, lit = 0, mapLit = 0;
    for (int y = 0; y < 48; ++y) {
      for (int x = 0; x < 64; ++x) {
        const Ray ray = camera.generateRay({float(x) + 0.5f, float(y) + 0.5f});
        const std::optional<Hit> hit = prepared.bvh().intersect(ray, 1e30f);
        if (!hit) continue;
        const SurfaceHit s = prepared.scene().geometry.surface(ray, *hit, false, false);
        if (s.p.x > 0.0f) continue;  // the lit room, seen past the wall's end
        const glm::vec3 n = glm::dot(s.ns, ray.d) > 0.0f ? -s.ns : s.ns;
        ++points;
        lit += field.irradiance(s.p, n, &prepared.bvh()).irradiance != glm::vec3(0.0f) ? 1 : 0;
        mapLit += field.irradiance(s.p, n).irradiance != glm::vec3(0.0f) ? 1 : 0;
      }
    }
    std::printf("field %d, %d: %d points in the dark room, %d lit by the map alone, %d once confirmed\n",
                settings.probes, settings.rays, points, mapLit, lit);
    EXPECT_GT(points, 64 * 48 / 2);
    EXPECT_EQ(lit, 0) << settings.probes << " probes, " << settings.rays << " rays";
  }
}

// A closed box with a lamp inside it, on a wide floor: the probes inside the
// box are full of light, and no point outside it receives any.
TEST(FieldHybrid, AProbeInsideAClosedBoxLightsNothingOutside) {
  json objects = json::array();
  objects.push_back(quad({{-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, {-3, 0, 3}}, "w"));  // the floor
  const double a = 0.01, b = 1.5;  // the box: [-0.75, 0.75] x [a, b] x [-0.75, 0.75]
  objects.push_back(quad({{-0.75, a, -0.75}, {0.75, a, -0.75}, {0.75, a, 0.75}, {-0.75, a, 0.75}}, "w"));
  objects.push_back(quad({{-0.75, b, -0.75}, {-0.75, b, 0.75}, {0.75, b, 0.75}, {0.75, b, -0.75}}, "w"));
  objects.push_back(quad({{-0.75, a, -0.75}, {-0.75, b, -0.75}, {0.75, b, -0.75}, {0.75, a, -0.75}}, "w"));
  objects.push_back(quad({{-0.75, a, 0.75}, {0.75, a, 0.75}, {0.75, b, 0.75}, {-0.75, b, 0.75}}, "w"));
  objects.push_back(quad({{-0.75, a, -0.75}, {-0.75, a, 0.75}, {-0.75, b, 0.75}, {-0.75, b, -0.75}}, "w"));
  objects.push_back(quad({{0.75, a, -0.75}, {0.75, b, -0.75}, {0.75, b, 0.75}, {0.75, a, 0.75}}, "w"));
  objects.push_back(quad({{-0.2, 1.4, -0.2}, {-0.2, 1.4, 0.2}, {0.2, 1.4, 0.2}, {0.2, 1.4, -0.2}}, "lamp"));
  const json scene = {
      {"glint", 1},
      {"image", {{"width", 32}, {"height", 32}}},
      {"camera", {{"eye", {0, 3, -4}}, {"look_at", {0, 0, 0}}, {"fov_y", 60}}},
      {"tracing", {{"transport", "path"}, {"max_bounces", 4}}},
      {"materials",
       {{"w", {{"color", {0.8, 0.8, 0.8}}, {"diffuse", 1}}},
        {"lamp", {{"color", {0.8, 0.8, 0.8}}, {"diffuse", 1}, {"emission", {20, 20, 20}}}}}},
      {"objects", objects}};
  const PreparedScene prepared(test::sceneFromJson(scene.dump()), BvhSettings{});
  const FrameSettings frame = centreRays(prepared.scene(), 32, 32);
  RayStats stats;
  const IrradianceField field = buildField(prepared, frame, {8, 256}, stats);
  int inside = 0, outside = 0, lit = 0, mapLit = 0;
  for (int i = 0; i < field.probeCount(); ++i) {
    const glm::vec3 p = field.position(i);
    const bool in = std::abs(p.x) < 0.75f && std::abs(p.z) < 0.75f && p.y > a && p.y < b;
    inside += in && field.probe(i).irradiance[0] != glm::vec3(0.0f) ? 1 : 0;
  }
  for (float x = -2.9f; x < 3.0f; x += 0.1f) {
    for (float z = -2.9f; z < 3.0f; z += 0.1f) {
      if (std::abs(x) < 0.8f && std::abs(z) < 0.8f) continue;
      ++outside;
      lit += field.irradiance({x, 0.0f, z}, {0, 1, 0}, &prepared.bvh()).irradiance != glm::vec3(0.0f) ? 1 : 0;
      mapLit += field.irradiance({x, 0.0f, z}, {0, 1, 0}).irradiance != glm::vec3(0.0f) ? 1 : 0;
    }
  }
  std::printf("closed box: %d lit probes inside, %d floor points outside, %d lit by the map alone, %d once confirmed\n",
              inside, outside, mapLit, lit);
  EXPECT_GT(inside, 0);
  EXPECT_GT(outside, 1000);
  EXPECT_EQ(lit, 0);
}

}  // namespace
}  // namespace glint
