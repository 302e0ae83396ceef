// The hybrid frame: OpenGL (OSMesa) draws what the tracer computes for
// direct light, masks exactly the objects the rule names, and the traced
// pixels land in the frame unchanged, in process and through glintd.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <set>
#include <string_view>
#include <thread>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "client/farm/distributed_tile_service.h"
#include "client/raster/hybrid_frame.h"
#include "client/raster/image_rows.h"
#include "client/raster/offscreen_context.h"
#include "client/raster/pixel_mark.h"
#include "client/commands/provenance.h"
#include "client/raster/raster_scene.h"
#include "common/base/file_source.h"
#include "common/image/encoding.h"
#include "common/render/mask_rule.h"
#include "common/render/renderer.h"
#include "common/scene/scene_load.h"
#include "proto/scene_bundle.h"
#include "tests/support/background_server.h"
#include "server/log.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

struct SceneSetup {
  proto::LoadedBundle loaded;
  FrameSettings frame;
};

SceneSetup loadFile(const std::string& path, int width = 160, int height = 120) {
  SceneSetup s{proto::loadSceneBundle(path), {}};
  s.frame = s.loaded.scene.frame;
  s.frame.width = width;
  s.frame.height = height;
  return s;
}

SceneSetup load(const char* scene, int width = 160, int height = 120) {
  return loadFile(test::sourcePath(scene), width, height);
}

// The frame traced with direct light only (what a pixel OpenGL would shade
// gets when it is traced for its shadows).
FrameImage directLight(TileService& service, FrameSettings frame) {
  frame.tracing.maxDepth = 1;
  return renderFrame(service, frame, {}).image;
}

// A mask rule with the default thresholds; without shadow maps unless asked.
MaskSettings rule(MaskRule rule, int shadowMap = 0) {
  MaskSettings mask;
  mask.rule = rule;
  mask.shadowMap = shadowMap;
  return mask;
}

// A glintd on loopback's next free port with `threads` tracing threads, its
// log off.
server::ServerOptions quietLoopback(int threads) {
  server::setLogging(false);
  server::ServerOptions o;
  o.listen = "127.0.0.1:0";
  o.threads = threads;
  o.handleSignals = false;
  return o;
}

HybridResult hybrid(const Scene& scene, TileService& service, const FrameSettings& frame, const MaskSettings& mask,
                    int tileSize = 32) {
  gl::OffscreenContext context(frame.width, frame.height);
  gl::RasterScene raster(context.api(), scene);
  HybridResult result;
  renderHybrid(context.api(), raster, service, frame, mask, tileSize, result);
  return result;
}

// The channels of a hybrid frame's traced pixels that differ from the full
// trace of their kind: with direct light (`direct`), or in full (`full`).
int tracedUnlikeTheTrace(const HybridResult& here, const FrameImage& direct, const FrameImage& full) {
  int differing = 0;
  for (std::size_t i = 0; i < here.mask.size(); ++i) {
    if (here.mask[i] == kRasterPixel) continue;
    const FrameImage& expected = tracedWithDirectLight(here.mask[i]) ? direct : full;
    for (int k = 0; k < 3; ++k) differing += here.image.rgb[3 * i + k] != expected.rgb[3 * i + k] ? 1 : 0;
  }
  return differing;
}

// A frame's hybrid under the scene's own mask, with the full trace, and the
// channels of its traced pixels unlike the full trace of their kind.
struct AgainstTheTrace {
  HybridResult here;
  FrameImage full;
  int tracedUnlike;
};
AgainstTheTrace hybridAgainstTheTrace(const Scene& scene, TileService& local, const FrameSettings& frame) {
  AgainstTheTrace a{hybrid(scene, local, frame, scene.mask), renderFrame(local, frame, {}).image, 0};
  a.tracedUnlike = tracedUnlikeTheTrace(a.here, directLight(local, frame), a.full);
  return a;
}

// A pixel is "fully covered" when rays through its centre and four points
// `margin` pixels off it diagonally (0.45: near its corners) hit the same
// primitive with the same texture colour (`sameColour`): no silhouette or
// (with sameColour) checker edge passes that close to the centre.
std::vector<bool> fullyCovered(const PreparedScene& prepared, const FrameSettings& frame, float margin = 0.45f,
                               bool sameColour = true) {
  const Scene& scene = prepared.scene();
  const Camera camera(frame.camera, frame.width, frame.height);
  std::vector<bool> covered(static_cast<std::size_t>(frame.width * frame.height), false);
  const auto probe = [&](float x, float y) -> std::pair<long long, glm::vec3> {
    const Ray ray = camera.generateRay({x, y});
    const auto hit = prepared.bvh().intersect(ray, 1e30f);
    if (!hit) return {-1, glm::vec3(0.0f)};
    const SurfaceHit s = scene.geometry.surface(ray, *hit);
    const Material& m = scene.materials[scene.geometry.materialOf(hit->prim)];
    return {hit->prim, m.texture >= 0 ? scene.textures[static_cast<std::size_t>(m.texture)].evaluate(s.uv) : m.color};
  };
  for (int y = 0; y < frame.height; ++y) {
    for (int x = 0; x < frame.width; ++x) {
      const auto centre = probe(x + 0.5f, y + 0.5f);
      bool same = true;
      for (const glm::vec2 o : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(-1, 1), glm::vec2(1, 1)}) {
        const auto p = probe(x + 0.5f + margin * o.x, y + 0.5f + margin * o.y);
        same = same && p.first == centre.first && (!sameColour || p.second == centre.second);
      }
      covered[static_cast<std::size_t>(y * frame.width + x)] = same;
    }
  }
  return covered;
}

// GL draws a surface as the tracer's direct light (no shadow rays, no
// secondary rays, one sample at the pixel centre): within 2/255 per channel
// on every fully covered pixel.
void expectRasterMatchesDirectTrace(const char* sceneFile, const OutputSettings& output = {}) {
  SceneSetup s = load(sceneFile);
  s.frame.sampling = {SamplePattern::kRegular, 1, FilterType::kBox, 0};
  s.frame.output = output;
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  const Renderer renderer(prepared, s.frame, test::directLightOnly(prepared.scene(), s.frame));
  ThreadPool pool(2);
  const FrameImage traced = renderFrame(renderer, pool, {}).image;

  LocalTileService service(prepared, pool);
  const HybridResult gl = hybrid(prepared.scene(), service, s.frame, rule(MaskRule::kNone));
  EXPECT_EQ(gl.maskedPixels, 0u);
  const std::vector<bool> covered = fullyCovered(prepared, s.frame);
  int compared = 0, worst = 0, bad = 0;
  for (std::size_t i = 0; i < covered.size(); ++i) {
    if (!covered[i]) continue;
    ++compared;
    int d = 0;
    for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(gl.image.rgb[3 * i + k] - traced.rgb[3 * i + k]));
    if (d > 2 && bad++ < 5) {
      ADD_FAILURE() << sceneFile << " pixel " << i % static_cast<std::size_t>(s.frame.width) << ","
                    << i / static_cast<std::size_t>(s.frame.width) << " gl " << int(gl.image.rgb[3 * i]) << " "
                    << int(gl.image.rgb[3 * i + 1]) << " " << int(gl.image.rgb[3 * i + 2]) << " traced "
                    << int(traced.rgb[3 * i]) << " " << int(traced.rgb[3 * i + 1]) << " " << int(traced.rgb[3 * i + 2]);
    }
    worst = std::max(worst, d);
  }
  EXPECT_EQ(bad, 0) << sceneFile;
  EXPECT_LE(worst, 2) << sceneFile;
  EXPECT_GT(compared, static_cast<int>(covered.size()) / 2) << sceneFile;
}

// A GL-only frame of an analytic scene: a diffuse, specular sphere lit by one
// point light, every pixel computed here in double precision from the
// scene's definition (gluLookAt / gluPerspective rays, Lambert and Phong),
// stored as it is (the linear encoding).
TEST(Hybrid, RasterOfAnAnalyticSphere) {
  const Scene scene = test::sceneFromJson(R"({
    "glint": 1, "image": {"width": 64, "height": 64, "encoding": "linear"},
    "camera": {"eye": [0, 0, 6], "look_at": [0, 0, 0], "fov_y": 30},
    "materials": {"m": {"color": [1, 0.5, 0.25], "ambient": 0.05, "diffuse": 0.7, "specular": 0.4, "shininess": 20}},
    "lights": [{"type": "point", "position": [3, 4, 5], "attenuation": [1, 0.02, 0.01]}],
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
  const PreparedScene prepared(scene, BvhSettings{});
  ThreadPool pool(1);
  LocalTileService service(prepared, pool);
  const HybridResult gl = hybrid(scene, service, scene.frame, rule(MaskRule::kNone));
  const double tanHalf = std::tan(15.0 * M_PI / 180.0);
  const glm::dvec3 eye(0, 0, 6), light(3, 4, 5), c(1.0, 0.5, 0.25);
  int compared = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const glm::dvec3 d = glm::normalize(
          glm::dvec3((2.0 * (x + 0.5) / 64 - 1.0) * tanHalf, (1.0 - 2.0 * (y + 0.5) / 64) * tanHalf, -1.0));
      const double b = glm::dot(eye, d);
      const double disc = b * b - (glm::dot(eye, eye) - 1.0);
      if (std::abs(disc) < 0.02) continue;  // the silhouette
      glm::dvec3 want(0.0);
      if (disc > 0.0) {
        const glm::dvec3 p = eye + (-b - std::sqrt(disc)) * d;
        const glm::dvec3 n = glm::normalize(p);
        const double dist = glm::length(light - p);
        const glm::dvec3 l = (light - p) / dist;
        want = c * 0.05;
        const double nl = glm::dot(n, l);
        if (nl > 0.0) {
          const double li = 1.0 / (1.0 + 0.02 * dist + 0.01 * dist * dist);
          want += li * c * 0.7 * nl;
          const double vr = glm::dot(-d, 2.0 * nl * n - l);
          if (vr > 0.0) want += glm::dvec3(li * 0.4 * std::pow(vr, 20.0));
        }
      }
      want = glm::clamp(want, 0.0, 1.0) * 255.0;
      const auto i = static_cast<std::size_t>(y * 64 + x) * 3;
      ASSERT_NEAR(gl.image.rgb[i], want.r, 2.0) << x << "," << y;
      ASSERT_NEAR(gl.image.rgb[i + 1], want.g, 2.0) << x << "," << y;
      ASSERT_NEAR(gl.image.rgb[i + 2], want.b, 2.0) << x << "," << y;
      ++compared;
    }
  }
  EXPECT_GT(compared, 64 * 64 * 9 / 10);
}

TEST(Hybrid, RasterMatchesTheTracersDirectLight) {
  expectRasterMatchesDirectTrace("scenes/room.json");
  expectRasterMatchesDirectTrace("scenes/glass.json");
  expectRasterMatchesDirectTrace("scenes/bunny.json");
  expectRasterMatchesDirectTrace("scenes/hard/poster.json");  // 2 mm in front of a wall 60 units away
  expectRasterMatchesDirectTrace("scenes/lights.json");       // a spot light's cones, a directional light
}

int channelDifference(const FrameImage& a, const FrameImage& b, std::size_t pixel) {
  int d = 0;
  for (std::size_t k = 3 * pixel; k < 3 * pixel + 3; ++k) d = std::max(d, std::abs(a.rgb[k] - b.rgb[k]));
  return d;
}

// One frame of a prepared scene drawn by OpenGL alone (mask none) and as the
// tracer's direct light.
struct RasterAndTrace {
  FrameImage traced;
  HybridResult gl;
};
RasterAndTrace rasterAndDirectTrace(const PreparedScene& prepared) {
  const Scene& scene = prepared.scene();
  ThreadPool pool(2);
  RasterAndTrace r;
  r.traced = renderFrame(Renderer(prepared, scene.frame, test::directLightOnly(scene, scene.frame)), pool, {}).image;
  LocalTileService service(prepared, pool);
  r.gl = hybrid(scene, service, scene.frame, rule(MaskRule::kNone));
  return r;
}

// Of the `covered` pixels (counted in `compared`), those where the raster is
// more than 2/255 from the trace in some channel.
int offByMoreThanTwo(const RasterAndTrace& r, const std::vector<bool>& covered, int& compared) {
  int bad = 0;
  compared = 0;
  for (std::size_t i = 0; i < covered.size(); ++i) {
    if (!covered[i]) continue;
    ++compared;
    bad += channelDifference(r.gl.image, r.traced, i) > 2 ? 1 : 0;
  }
  return bad;
}

// Shadow maps: surfaces OpenGL draws get the shadows the tracer's shadow
// rays find. Every fully covered pixel GL keeps (the maps decided it) equals
// the tracer's direct light with shadow rays within 2/255; in the room with
// its floor left to GL (the thesis's scene 2) hundreds of them lie in the
// gold sphere's shadow, and without the maps each of those is lit. The
// pixels the maps cannot decide are traced (MaskedPixelsEqualTheFullTrace
// proves them the full trace's). Also where the maps' precision is tested
// hardest: a light 0.25 above a floor 60 wide (long shadows, the floor lit
// at grazing angles) and the room 1000 times larger, 1e5 from the origin.
TEST(Hybrid, RasterSurfacesReceiveShadows) {
  for (const char* sceneFile :
       {"scenes/room-gl-floor.json", "scenes/room.json", "scenes/glass.json", "scenes/bunny.json",
        "scenes/hard/grazing-shadow.json", "scenes/hard/shadow-far.json"}) {
    SceneSetup s = load(sceneFile);
    s.frame.sampling = {SamplePattern::kRegular, 1, FilterType::kBox, 0};
    const PreparedScene prepared(s.loaded.scene, BvhSettings{});
    const Scene& scene = prepared.scene();
    ThreadPool pool(2);
    const EffectPlan unshadowedPlan = test::directLightOnly(scene, s.frame);
    EffectPlan shadowedPlan = unshadowedPlan;
    shadowedPlan.shadows = EffectPlan::derive(scene, s.frame).shadows;
    const FrameImage shadowed = renderFrame(Renderer(prepared, s.frame, shadowedPlan), pool, {}).image;
    const FrameImage unshadowed = renderFrame(Renderer(prepared, s.frame, unshadowedPlan), pool, {}).image;
    LocalTileService service(prepared, pool);
    const HybridResult maps = hybrid(scene, service, s.frame, rule(MaskRule::kAuto, 1024));
    const HybridResult noMaps = hybrid(scene, service, s.frame, rule(MaskRule::kAuto, 0));
    const std::vector<bool> covered = fullyCovered(prepared, s.frame);
    int compared = 0, bad = 0, inShadow = 0, litWithoutMaps = 0;
    for (std::size_t i = 0; i < covered.size(); ++i) {
      if (!covered[i] || maps.mask[i] != kRasterPixel) continue;
      ++compared;
      if (channelDifference(maps.image, shadowed, i) > 2 && bad++ < 5) {
        ADD_FAILURE() << sceneFile << " pixel " << i % 160 << "," << i / 160 << " differs from the traced shadow";
      }
      if (channelDifference(shadowed, unshadowed, i) > 8) {
        ++inShadow;
        litWithoutMaps += channelDifference(noMaps.image, shadowed, i) > 8 ? 1 : 0;
      }
    }
    std::printf("%s: %d GL pixels compared, %d in shadow, %zu traced for shadow edges\n", sceneFile, compared, inShadow,
                maps.shadowEdgePixels);
    EXPECT_EQ(bad, 0) << sceneFile;
    EXPECT_GT(compared, static_cast<int>(covered.size()) / 3) << sceneFile;
    EXPECT_EQ(litWithoutMaps, inShadow) << sceneFile;
    if (std::string(sceneFile) == "scenes/room-gl-floor.json") {
      EXPECT_GT(inShadow, 50);
    }
  }
}

// A dense mesh (a terrain of 320,000 triangles, most smaller than a pixel):
// no pixel whose centre lies clear of a facet's edge (by 1/32 pixel, more
// than GL's snapping of vertices to 1/256 pixel moves an edge) is left lit by
// ambient alone where the tracer's direct light reaches it. With the
// projection's depth (24 bits, near = far / 1000) the nearer of two close
// surfaces was not always the one drawn; the shaders now write the exact
// distance, linear.
TEST(Hybrid, DenseMeshHasNoStrayAmbientPixels) {
  std::string obj;
  constexpr int n = 400;
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x) {
      const double X = x * 4.0 / n - 2.0, Z = y * 4.0 / n - 2.0;
      const double h =
          0.3 * std::sin(3 * X) * std::cos(2 * Z) + 0.1 * std::sin(13 * X + 7 * Z) + 0.05 * std::cos(29 * Z - 17 * X);
      obj += "v " + std::to_string(X) + " " + std::to_string(h) + " " + std::to_string(Z) + "\n";
    }
  }
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x + 1;
      obj += "f " + std::to_string(a) + " " + std::to_string(a + n + 1) + " " + std::to_string(a + 1) + "\nf " +
             std::to_string(a + 1) + " " + std::to_string(a + n + 1) + " " + std::to_string(a + n + 2) + "\n";
    }
  }
  MemorySource files;
  files.add("terrain.obj", obj);
  const Scene scene = loadScene(R"({"glint": 1, "image": {"width": 320, "height": 240},
      "camera": {"eye": [0, 2.5, 3.5], "look_at": [0, 0, 0]}, "lights": [{"type": "point", "position": [2, 4, 3]}],
      "materials": {"m": {"color": [0.9, 0.8, 0.6], "ambient": 0.1, "diffuse": 0.8}},
      "objects": [{"type": "mesh", "file": "terrain.obj", "material": "m"}]})",
                                files);
  const PreparedScene prepared(scene, BvhSettings{});
  const auto [traced, gl] = rasterAndDirectTrace(prepared);
  const std::vector<bool> covered = fullyCovered(prepared, scene.frame, 1.0f / 32.0f);
  int stray = 0, off = 0, compared = 0;
  for (std::size_t i = 0; i < traced.rgb.size(); i += 3) {
    if (!covered[i / 3]) continue;
    ++compared;
    bool darker = true, far = false;
    for (int k = 0; k < 3; ++k) {
      darker = darker && gl.image.rgb[i + k] + 24 < traced.rgb[i + k];
      far = far || std::abs(gl.image.rgb[i + k] - traced.rgb[i + k]) > 8;
    }
    stray += darker ? 1 : 0;
    off += far ? 1 : 0;
  }
  EXPECT_GT(compared, static_cast<int>(covered.size()) * 3 / 4);
  EXPECT_EQ(stray, 0);
  EXPECT_LT(off, compared / 1000) << off << " of " << compared << " pixels more than 8/255 off";
}

// With 4 samples a pixel the raster's edges are traced: on the pixels an
// object's edge crosses (rays through the pixel meet different primitives),
// the hybrid frame is measurably closer to the converged direct light (the
// tracer's, 64 samples a pixel) than the raster at one sample a pixel.
// Nothing is masked for its reflectivity (threshold 1; the glass is masked
// for its transparency, and its pixels are not counted) and there are no
// shadow maps. (Checker squares smaller than a pixel, at the room's horizon,
// alias with 4 samples whichever way they are placed; they are not counted.)
TEST(Hybrid, TracedEdgesAreCloserToTheTrace) {
  for (const char* sceneFile : {"scenes/room.json", "scenes/glass.json"}) {
    SceneSetup s = load(sceneFile);
    s.frame.sampling = {SamplePattern::kRegular, 4, FilterType::kBox, 0};
    const PreparedScene prepared(s.loaded.scene, BvhSettings{});
    ThreadPool pool(2);
    FrameSettings converged = s.frame;
    converged.sampling.samples = 64;
    const FrameImage traced =
        renderFrame(Renderer(prepared, converged, test::directLightOnly(prepared.scene(), converged)), pool, {}).image;
    LocalTileService service(prepared, pool);
    MaskSettings edgesOnly = rule(MaskRule::kAuto);
    edgesOnly.minReflectivity = 1.0f;
    FrameSettings single = s.frame;
    single.sampling.samples = 1;
    const HybridResult aliased = hybrid(prepared.scene(), service, single, edgesOnly);
    const HybridResult smooth = hybrid(prepared.scene(), service, s.frame, edgesOnly);
    EXPECT_EQ(smooth.maskedPixels, smooth.rasterEdgePixels + aliased.maskedPixels) << sceneFile;
    EXPECT_GT(smooth.rasterEdgePixels, 100u) << sceneFile;
    EXPECT_LT(smooth.rasterEdgePixels, smooth.mask.size() / 5) << sceneFile;
    const std::vector<bool> covered = fullyCovered(prepared, s.frame, 0.45f, false);
    double aliasedError = 0.0, smoothError = 0.0;
    for (std::size_t i = 0; i < covered.size(); ++i) {
      if (covered[i] || smooth.mask[i] == kMaskedPixel) continue;
      for (std::size_t k = 3 * i; k < 3 * i + 3; ++k) {
        aliasedError += std::abs(aliased.image.rgb[k] - traced.rgb[k]);
        smoothError += std::abs(smooth.image.rgb[k] - traced.rgb[k]);
      }
    }
    std::printf("%s: edge error one sample %.0f, edges traced %.0f (%zu pixels of %zu)\n", sceneFile, aliasedError,
                smoothError, smooth.rasterEdgePixels, smooth.mask.size());
    EXPECT_LT(smoothError, 0.6 * aliasedError) << sceneFile;
  }
}

TEST(Hybrid, RasterEncodesAsTheTracer) {
  expectRasterMatchesDirectTrace("scenes/room.json", {Encoding::kSrgb, 0.0f});
  expectRasterMatchesDirectTrace("scenes/glass.json", {Encoding::kLinear, 1.5f});
  expectRasterMatchesDirectTrace("scenes/bunny.json", {Encoding::kSrgb, -0.5f});
}

// A pixel is masked exactly when the object the tracer's primary ray meets
// at the pixel centre is masked (silhouette pixels aside, where GL and the
// ray may see different objects).
TEST(Hybrid, MaskFollowsTheObjectAtThePixelCentre) {
  const SceneSetup s = load("scenes/room.json");
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService service(prepared, pool);
  const MaskSettings mask = prepared.scene().mask;
  const HybridResult h = hybrid(prepared.scene(), service, s.frame, mask);
  const Camera camera(s.frame.camera, s.frame.width, s.frame.height);
  const std::vector<bool> covered = fullyCovered(prepared, s.frame);
  int mismatches = 0, masked = 0;
  for (int y = 0; y < s.frame.height; ++y) {
    for (int x = 0; x < s.frame.width; ++x) {
      const auto i = static_cast<std::size_t>(y * s.frame.width + x);
      const Ray ray = camera.generateRay({x + 0.5f, y + 0.5f});
      const auto hit = prepared.bvh().intersect(ray, 1e30f);
      const bool expected =
          hit && materialMasked(prepared.scene().materials[prepared.scene().geometry.materialOf(hit->prim)], mask);
      masked += expected ? 1 : 0;
      if (covered[i] && expected != (markOf(h.surface[i]) == kMaskedPixel)) ++mismatches;
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(masked, 1000);
  const auto marked = [&](PixelMark mark) {
    return static_cast<std::size_t>(std::count(h.mask.begin(), h.mask.end(), mark));
  };
  std::size_t changedByEdges = 0;
  for (std::size_t i = 0; i < h.mask.size(); ++i) changedByEdges += h.mask[i] != markOf(h.surface[i]) ? 1 : 0;
  EXPECT_EQ(h.maskedPixels, h.mask.size() - marked(kRasterPixel));
  EXPECT_EQ(h.shadowEdgePixels, marked(kShadowEdgePixel));
  EXPECT_EQ(h.rasterEdgePixels, changedByEdges);
  EXPECT_GT(h.rasterEdgePixels, 0u);
}

// Masked pixels of the hybrid frame are the full trace's, byte for byte, in
// process and through a glintd on loopback; the pixels traced for a shadow's
// edge are the full trace's with direct light alone (max depth 1: the
// tracer's shadows, no reflected rays, as OpenGL draws their neighbours).
TEST(Hybrid, MaskedPixelsEqualTheFullTrace) {
  const SceneSetup s = load("scenes/room.json");
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  const FrameImage full = renderFrame(local, s.frame, {}).image;
  const FrameImage directFull = directLight(local, s.frame);

  server::BackgroundServer glintd(quietLoopback(2));
  DistributedTileService remote(resolveServers({glintd.address()}), s.loaded.bundle);

  for (TileService* service : {static_cast<TileService*>(&local), static_cast<TileService*>(&remote)}) {
    const HybridResult h = hybrid(prepared.scene(), *service, s.frame, prepared.scene().mask);
    int differing = 0, edges = 0, edgesDiffering = 0, edgesUnlikeFullTrace = 0;
    for (std::size_t i = 0; i < h.mask.size(); ++i) {
      if (h.mask[i] == kRasterPixel) continue;
      const FrameImage& expected = tracedWithDirectLight(h.mask[i]) ? directFull : full;
      edges += tracedWithDirectLight(h.mask[i]) ? 1 : 0;
      for (int k = 0; k < 3; ++k) {
        const bool off = h.image.rgb[3 * i + k] != expected.rgb[3 * i + k];
        differing += off ? 1 : 0;
        if (tracedWithDirectLight(h.mask[i])) {
          edgesDiffering += off ? 1 : 0;
          edgesUnlikeFullTrace += h.image.rgb[3 * i + k] != full.rgb[3 * i + k] ? 1 : 0;
        }
      }
    }
    EXPECT_EQ(differing, 0);
    EXPECT_EQ(edgesDiffering, 0);
    EXPECT_GT(edges, 50);
    EXPECT_GT(edgesUnlikeFullTrace, 0);  // the floor reflects in the full trace, not in direct light
    EXPECT_GT(h.maskedPixels, 5000u);
    EXPECT_GT(h.tiles, 0);
  }
  // Under "all" the hybrid frame is the full trace.
  EXPECT_EQ(hybrid(prepared.scene(), local, s.frame, rule(MaskRule::kAll)).image.rgb, full.rgb);
  // The output encoding travels to the server: sRGB at +1 EV, the same bytes.
  FrameSettings encoded = s.frame;
  encoded.output = {Encoding::kSrgb, 1.0f};
  const FrameImage here = renderFrame(local, encoded, {}).image;
  EXPECT_EQ(renderFrame(remote, encoded, {}).image.rgb, here.rgb);
  EXPECT_NE(here.rgb, full.rgb);
}

// The perceptual rule: its traced pixels are the tracer's own with the
// perceptual pattern (the masked ones the full trace's, the others its
// direct light: each pixel's decision hangs on its neighbours' probes alone),
// alike in process, through glintd and for any tile size; it casts fewer
// rays than auto (the share falls as the image grows: edges are a smaller
// part of it), and traces the raster's visible colour edges, which auto
// leaves to OpenGL (the glass scene's checker floor).
TEST(Hybrid, PerceptualRuleTracesItsPixelsAlikeEverywhere) {
  const SceneSetup s = load("scenes/room.json");
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  FrameSettings perceptual = s.frame;
  perceptual.sampling.pattern = SamplePattern::kPerceptual;
  const FrameImage full = renderFrame(local, perceptual, {}).image;
  perceptual.tracing.maxDepth = 1;
  const FrameImage direct = renderFrame(local, perceptual, {}).image;
  server::BackgroundServer glintd(quietLoopback(2));
  DistributedTileService remote(resolveServers({glintd.address()}), s.loaded.bundle);
  MaskSettings mask = prepared.scene().mask;
  mask.rule = MaskRule::kPerceptual;
  const HybridResult here = hybrid(prepared.scene(), local, s.frame, mask);
  const int differing = tracedUnlikeTheTrace(here, direct, full);
  EXPECT_EQ(differing, 0);
  EXPECT_GT(here.maskedPixels, 5000u);
  EXPECT_EQ(hybrid(prepared.scene(), local, s.frame, mask, 7).image.rgb, here.image.rgb);
  EXPECT_EQ(hybrid(prepared.scene(), remote, s.frame, mask).image.rgb, here.image.rgb);
  const HybridResult automatic = hybrid(prepared.scene(), local, s.frame, prepared.scene().mask);
  EXPECT_LT(here.rays.total(), automatic.rays.total());  // 75 % at this size; 42 % at 640 x 480 (bench)

  const SceneSetup glass = load("scenes/glass.json");
  const PreparedScene glassScene(glass.loaded.scene, BvhSettings{});
  LocalTileService glassService(glassScene, pool);
  MaskSettings glassMask = glassScene.scene().mask;
  const std::size_t autoEdges = hybrid(glassScene.scene(), glassService, glass.frame, glassMask).rasterEdgePixels;
  glassMask.rule = MaskRule::kPerceptual;
  EXPECT_GT(hybrid(glassScene.scene(), glassService, glass.frame, glassMask).rasterEdgePixels, autoEdges + 300);
}

// A soft light's shadows on surfaces OpenGL draws: the raster shades its
// unshadowed light, the pixels not proved to see it whole are traced (with
// direct light, as an undecided shadow), and the frame is the full trace's
// within 8/255 while casting a fraction of its shadow rays; the traced
// pixels are the full trace's to the byte, here, split into other tiles and
// through a glintd.
void expectOnlyWhereTheLightMayBeBlocked(const char* scene) {
  SCOPED_TRACE(scene);
  const SceneSetup s = load(scene);
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  const FrameResult full = renderFrame(local, s.frame, {});
  const FrameImage direct = directLight(local, s.frame);
  const MaskSettings mask = prepared.scene().mask;
  const HybridResult here = hybrid(prepared.scene(), local, s.frame, mask);
  const int differing = tracedUnlikeTheTrace(here, direct, full.image);
  // One sample at each pixel's centre, where OpenGL shades: the soft shadow
  // OpenGL's pixels and the traced ones make is the full trace's. (With the
  // scene's tent filter the full trace's pixel also holds its neighbours'
  // light, which differs by up to 14/255 where the penumbra starts at the
  // cube's foot.)
  FrameSettings centre = s.frame;
  centre.sampling = {SamplePattern::kRegular, 1, FilterType::kBox, 0};
  const FrameImage fullCentre = renderFrame(local, centre, {}).image;
  const HybridResult hybridCentre = hybrid(prepared.scene(), local, centre, mask);
  int worst = 0;
  for (std::size_t i = 0; i < here.mask.size(); ++i) {
    worst = std::max(worst, channelDifference(hybridCentre.image, fullCentre, i));
  }
  std::printf("%s: %zu pixels traced for the soft light, shadow rays %llu of the full trace's %llu; "
              "at the pixel centres at most %d/255 from the full trace\n",
              scene, here.shadowEdgePixels, static_cast<unsigned long long>(here.rays.shadow),
              static_cast<unsigned long long>(full.stats.shadow), worst);
  EXPECT_LE(worst, 8);
  EXPECT_EQ(differing, 0);
  EXPECT_GT(here.shadowEdgePixels, 500u);  // the penumbra and umbra are traced
  EXPECT_LT(here.shadowEdgePixels, here.mask.size() / 3);
  EXPECT_LT(here.rays.shadow * 100, full.stats.shadow * 35);
  EXPECT_EQ(hybrid(prepared.scene(), local, s.frame, mask, 7).image.rgb, here.image.rgb);
  server::BackgroundServer glintd(quietLoopback(2));
  DistributedTileService remote(resolveServers({glintd.address()}), s.loaded.bundle);
  EXPECT_EQ(hybrid(prepared.scene(), remote, s.frame, mask).image.rgb, here.image.rgb);
}

TEST(Hybrid, AreaLightsTracedOnlyWhereTheLightMayBeBlocked) {
  expectOnlyWhereTheLightMayBeBlocked("scenes/soft-shadows.json");
}

// An area light's points are bounded by memory alone in the raster, as in
// the tracer: 256 of them (more than the shaders' uniform arrays once held)
// draw, and the frame at the pixel centres is the full trace's within 8/255,
// its traced pixels the full trace's to the byte.
TEST(Hybrid, AnAreaLightOfManyPointsIsDrawn) {
  SceneSetup s = load("scenes/soft-shadows.json", 80, 60);
  s.frame.sampling = {SamplePattern::kRegular, 1, FilterType::kBox, 0};
  s.frame.sampling.lightSamples = 256;
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  const auto [here, full, tracedUnlike] = hybridAgainstTheTrace(prepared.scene(), local, s.frame);
  EXPECT_EQ(tracedUnlike, 0);
  int worst = 0;
  for (std::size_t i = 0; i < here.mask.size(); ++i) worst = std::max(worst, channelDifference(here.image, full, i));
  EXPECT_LE(worst, 8);
  EXPECT_LT(here.shadowEdgePixels, here.mask.size() / 2);  // the raster drew the rest
}

TEST(Hybrid, SphereLightsTracedOnlyWhereTheBallMayBeBlocked) {
  expectOnlyWhereTheLightMayBeBlocked("scenes/sphere-light.json");
}

// A sphere light far away, huge, tiny, holding the scene or low beside the
// objects: the proof decides or leaves the pixel to the tracer; the traced
// pixels are the full trace's to the byte, and at the pixel centres the
// frame is the full trace's within 8/255.
TEST(Hybrid, HostileSphereLightsStayTheFullTraces) {
  for (const auto& [position, radius] : std::vector<std::pair<glm::vec3, float>>{
           {glm::vec3(1e30f), 1e29f}, {{-1e38f, 1e38f, 0.0f}, 1e38f}, {{1.5f, 3.0f, 0.0f}, 3e38f},
           {{1.2f, 3.4f, 0.8f}, 1e-30f}, {{0.0f, 0.5f, 3.0f}, 0.2f}}) {
    SceneSetup s = load("scenes/sphere-light.json", 80, 60);
    s.loaded.scene.lights[0].position = position;
    s.loaded.scene.lights[0].radius = radius;
    s.frame.sampling = {SamplePattern::kRegular, 1, FilterType::kBox, 0};
    const PreparedScene prepared(s.loaded.scene, BvhSettings{});
    ThreadPool pool(2);
    LocalTileService local(prepared, pool);
    const auto [here, full, tracedUnlike] = hybridAgainstTheTrace(prepared.scene(), local, s.frame);
    EXPECT_EQ(tracedUnlike, 0) << radius;
    int worst = 0;
    for (std::size_t i = 0; i < here.mask.size(); ++i) worst = std::max(worst, channelDifference(here.image, full, i));
    EXPECT_LE(worst, 8) << radius;
  }
}

// Spot and directional lights: the spot's shadows come from its (point
// light's) cube map, the directional light's from its orthographic map; at
// the pixel centres the frame is the full trace's within 2/255, few pixels
// are left undecided, and the traced pixels are the full trace's to the
// byte, here and through a glintd.
TEST(Hybrid, SpotAndDirectionalShadowsFromTheirMaps) {
  const SceneSetup s = load("scenes/lights.json");
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  FrameSettings centre = s.frame;
  centre.sampling = {SamplePattern::kRegular, 1, FilterType::kBox, 0};
  const MaskSettings mask = prepared.scene().mask;
  const auto [here, full, tracedUnlike] = hybridAgainstTheTrace(prepared.scene(), local, centre);
  EXPECT_EQ(tracedUnlike, 0);
  const std::vector<bool> covered = fullyCovered(prepared, centre);
  int worst = 0, compared = 0;
  for (std::size_t i = 0; i < here.mask.size(); ++i) {
    if (!covered[i]) continue;
    worst = std::max(worst, channelDifference(here.image, full, i));
    ++compared;
  }
  std::printf("lights.json: %zu pixels traced for shadows; at the pixel centres at most %d/255 from the full trace\n",
              here.shadowEdgePixels, worst);
  EXPECT_LE(worst, 2);
  EXPECT_GT(compared, 10000);
  EXPECT_GT(here.shadowEdgePixels, 0u);  // the shadows' edges
  EXPECT_LT(here.shadowEdgePixels, here.mask.size() / 20);
  server::BackgroundServer glintd(quietLoopback(2));
  DistributedTileService remote(resolveServers({glintd.address()}), s.loaded.bundle);
  EXPECT_EQ(hybrid(prepared.scene(), remote, centre, mask).image.rgb, here.image.rgb);
  // Without maps the surfaces OpenGL draws take no shadow (the thesis's raster).
  const HybridResult unshadowed = hybrid(prepared.scene(), local, centre, rule(MaskRule::kAuto));
  int darker = 0;
  for (std::size_t i = 0; i < here.mask.size(); ++i) darker += channelDifference(unshadowed.image, here.image, i) > 8;
  EXPECT_GT(darker, 500);
}

// A rough reflector is traced where a mirror is (the mask rule's
// min_reflectivity), each traced pixel byte for byte the full trace's, in
// process, through glintd and for any tile size; the reflection's lobe is
// drawn (its pixels unlike the mirror's).
TEST(Hybrid, RoughReflectorsAreTracedAsTheFullTrace) {
  nlohmann::json room = nlohmann::json::parse(std::ifstream(test::sourcePath("scenes/room.json")));
  room["materials"]["mirror"]["roughness"] = 0.3;
  room["materials"]["floor"]["roughness"] = 0.2;
  const std::string path = test::scratchPath("rough-room.json").string();
  std::ofstream(path) << room.dump();
  const SceneSetup s = loadFile(path);
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ASSERT_TRUE(EffectPlan::derive(prepared.scene(), s.frame).glossyReflection);
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  const MaskSettings mask = prepared.scene().mask;
  const auto [here, full, tracedUnlike] = hybridAgainstTheTrace(prepared.scene(), local, s.frame);
  EXPECT_EQ(tracedUnlike, 0);
  EXPECT_GT(here.maskedPixels, 5000u);
  EXPECT_EQ(hybrid(prepared.scene(), local, s.frame, mask, 7).image.rgb, here.image.rgb);
  server::BackgroundServer glintd(quietLoopback(2));
  DistributedTileService remote(resolveServers({glintd.address()}), s.loaded.bundle);
  EXPECT_EQ(hybrid(prepared.scene(), remote, s.frame, mask).image.rgb, here.image.rgb);
  const SceneSetup mirror = load("scenes/room.json");
  const PreparedScene mirrorScene(mirror.loaded.scene, BvhSettings{});
  LocalTileService mirrorService(mirrorScene, pool);
  EXPECT_NE(renderFrame(mirrorService, mirror.frame, {}).image.rgb, full.rgb);
  std::remove(path.c_str());
}

// An environment image: OpenGL clears the background flat, so every pixel
// that shows no object is traced (and the raster's edges against one), byte
// for byte the full trace, here and through glintd (the scene's bundle
// carries the image); under none the flat background stays.
TEST(Hybrid, TheEnvironmentBehindEverythingIsTraced) {
  const SceneSetup s = load("scenes/environment.json");
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ASSERT_TRUE(EffectPlan::derive(prepared.scene(), s.frame).environment);
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  const MaskSettings mask = prepared.scene().mask;
  const auto [here, full, tracedUnlike] = hybridAgainstTheTrace(prepared.scene(), local, s.frame);
  EXPECT_EQ(tracedUnlike, 0);
  std::size_t sky = 0, raster = 0;
  for (std::size_t i = 0; i < here.mask.size(); ++i) {
    if (here.surface[i] >> kPixelMarkBits != 0) {
      raster += here.mask[i] == kRasterPixel ? 1 : 0;
      continue;
    }
    ++sky;
    EXPECT_EQ(here.mask[i], kMaskedPixel) << "pixel " << i;
  }
  EXPECT_GT(sky, 5000u);
  EXPECT_GT(raster, 3000u);  // the floor stays OpenGL's
  server::BackgroundServer glintd(quietLoopback(2));
  DistributedTileService remote(resolveServers({glintd.address()}), s.loaded.bundle);
  EXPECT_EQ(hybrid(prepared.scene(), remote, s.frame, mask).image.rgb, here.image.rgb);
  const HybridResult flat = hybrid(prepared.scene(), local, s.frame, rule(MaskRule::kNone));
  const Encoder encoder(s.frame.output);
  const glm::vec3 background = prepared.scene().background;
  for (std::size_t i = 0; i < flat.mask.size(); ++i) {
    if (flat.surface[i] >> kPixelMarkBits != 0) continue;
    ASSERT_EQ(flat.image.rgb[3 * i], encoder.byte(background.r)) << "pixel " << i;
    ASSERT_EQ(flat.image.rgb[3 * i + 2], encoder.byte(background.b)) << "pixel " << i;
  }
}

// A thin lens: OpenGL cannot blur, so every pixel whose point's circle of
// confusion exceeds half a pixel is traced with the frame's settings (and
// those a blur may reach), byte for byte the full trace's; a pinhole frame
// of the same scene traces none for the lens.
TEST(Hybrid, OutOfFocusPixelsAreTraced) {
  SceneSetup s = load("scenes/soft-shadows.json");
  s.frame.camera.aperture = 0.15f;
  s.frame.camera.focusDistance = glm::length(glm::vec3(-0.9f, 0.8f, 0.2f) - s.frame.camera.eye);  // the sphere
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  const MaskSettings mask = prepared.scene().mask;
  const auto [here, full, differing] = hybridAgainstTheTrace(prepared.scene(), local, s.frame);
  const Camera camera(s.frame.camera, s.frame.width, s.frame.height);
  const glm::vec3 forward = glm::normalize(s.frame.camera.lookAt - s.frame.camera.eye);
  int blurredLeft = 0, blurred = 0;
  for (std::size_t i = 0; i < here.mask.size(); ++i) {
    const int x = static_cast<int>(i % 160), y = static_cast<int>(i / 160);
    const Ray ray = camera.generateRay({x + 0.5f, y + 0.5f});
    const auto hit = prepared.bvh().intersect(ray, 1e30f);
    const float depth = hit ? hit->t * glm::dot(ray.d, forward) : 1e30f;
    if (camera.circleOfConfusion(depth) > 0.6f) {  // clear of the depth buffer's rounding
      ++blurred;
      blurredLeft += here.mask[i] == kRasterPixel ? 1 : 0;
    }
  }
  std::printf("lens: %d pixels blurred over half a pixel, %zu traced out of focus\n", blurred, here.outOfFocusPixels);
  EXPECT_GT(blurred, 1000);
  EXPECT_EQ(blurredLeft, 0);
  EXPECT_EQ(differing, 0);
  EXPECT_GE(here.outOfFocusPixels, static_cast<std::size_t>(blurred) / 2);
  EXPECT_EQ(hybrid(prepared.scene(), local, s.frame, mask, 7).image.rgb, here.image.rgb);
  s.frame.camera.aperture = 0.0f;
  EXPECT_EQ(hybrid(prepared.scene(), local, s.frame, mask).outOfFocusPixels, 0u);
}

// Counts the tiles a service is given.
class CountingService : public TileService {
 public:
  explicit CountingService(TileService& inner) : inner_(inner) {}
  void render(const FrameSettings& frame, std::span<const TileJob> jobs,
              const std::function<void(std::size_t, TileOutput&&)>& done) override {
    tiles += jobs.size();
    inner_.render(frame, jobs, done);
  }
  int parallelism() const override { return inner_.parallelism(); }
  void beginFrame() override { inner_.beginFrame(); }
  std::size_t tiles = 0;

 private:
  TileService& inner_;
};

// A frame the camera has left is abandoned between batches of tiles: the
// service is given no tile after cancelled() says so, renderHybrid returns
// false and the image stays the previous frame's; a check that never
// cancels gives the frame a plain call gives, byte for byte.
TEST(Hybrid, CancelledFrameStopsTracing) {
  SceneSetup s = load("scenes/room.json", 320, 240);
  s.frame.sampling.samples = 1;
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  CountingService counting(local);
  gl::OffscreenContext context(s.frame.width, s.frame.height);
  gl::RasterScene raster(context.api(), prepared.scene());
  const MaskSettings mask = prepared.scene().mask;
  HybridResult plain, checked;
  ASSERT_TRUE(renderHybrid(context.api(), raster, counting, s.frame, mask, 16, plain));
  const std::size_t all = counting.tiles;
  ASSERT_GT(all, 3 * 4 * 2u);  // more than three batches of 4 tiles a thread

  int checks = 0;
  counting.tiles = 0;
  const HybridControl neverCancelled{.cancelled =
                                         [&] {
                                           ++checks;
                                           return false;
                                         },
                                     .progress = {}};
  ASSERT_TRUE(renderHybrid(context.api(), raster, counting, s.frame, mask, 16, checked, std::nullopt, neverCancelled));
  EXPECT_EQ(checked.image.rgb, plain.image.rgb);
  EXPECT_EQ(counting.tiles, all);
  EXPECT_GT(checks, 2);

  FrameSettings moved = s.frame;
  moved.camera.eye.x += 0.5f;
  counting.tiles = 0;
  checks = 0;
  const HybridControl movesDuringTheFirstBatch{.cancelled = [&] { return ++checks > 1; }, .progress = {}};
  const bool finished =
      renderHybrid(context.api(), raster, counting, moved, mask, 16, checked, std::nullopt, movesDuringTheFirstBatch);
  EXPECT_FALSE(finished);
  EXPECT_EQ(counting.tiles, 4 * 2u);
  EXPECT_EQ(checked.image.rgb, plain.image.rgb);
}

// Progress counts the frame's traced pixels across its traced sets, row by
// row, never backwards, up to the pixels it traced, and changes nothing in
// the image.
TEST(Hybrid, ProgressCountsEveryTracedPixelOnce) {
  SceneSetup s = load("scenes/room.json", 320, 240);
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  gl::OffscreenContext context(s.frame.width, s.frame.height);
  gl::RasterScene raster(context.api(), prepared.scene());
  HybridResult plain, shown;
  ASSERT_TRUE(renderHybrid(context.api(), raster, local, s.frame, prepared.scene().mask, 32, plain));
  std::vector<std::pair<int, int>> told;
  const HybridControl control{.cancelled = {},
                              .progress = [&](int done, int total) { told.emplace_back(done, total); }};
  ASSERT_TRUE(
      renderHybrid(context.api(), raster, local, s.frame, prepared.scene().mask, 32, shown, std::nullopt, control));
  EXPECT_EQ(shown.image.rgb, plain.image.rgb);
  ASSERT_GT(told.size(), static_cast<std::size_t>(shown.tiles));  // row by row, finer than the tiles
  for (std::size_t i = 0; i < told.size(); ++i) {
    EXPECT_GT(told[i].first, i == 0 ? 0 : told[i - 1].first) << i;
    EXPECT_EQ(told[i].second, static_cast<int>(shown.maskedPixels)) << i;
  }
  EXPECT_EQ(told.back().first, static_cast<int>(shown.maskedPixels));
}

// A result passed back frame after frame (to keep its buffers) holds each
// frame as a fresh one would: nothing of the previous frame shows through,
// whatever its mask rule or size. (Both in contexts of one size: llvmpipe
// may round an interpolated position differently in a framebuffer of another
// size, and a pixel at a shadow map's decision boundary may then go the
// other way.)
TEST(Hybrid, ReusedResultEqualsAFreshOne) {
  const SceneSetup s = load("scenes/room.json");
  const PreparedScene prepared(s.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  const MaskSettings automatic = prepared.scene().mask;
  FrameSettings bigger = s.frame;
  bigger.width = 200;
  bigger.height = 150;
  HybridResult fresh;
  {
    gl::OffscreenContext context(bigger.width, bigger.height);
    gl::RasterScene raster(context.api(), prepared.scene());
    renderHybrid(context.api(), raster, local, s.frame, automatic, 32, fresh);
  }
  gl::OffscreenContext context(bigger.width, bigger.height);
  gl::RasterScene raster(context.api(), prepared.scene());
  HybridResult reused;
  renderHybrid(context.api(), raster, local, bigger, rule(MaskRule::kAll), 32, reused);
  renderHybrid(context.api(), raster, local, s.frame, automatic, 32, reused);
  EXPECT_EQ(reused.image.width, fresh.image.width);
  EXPECT_EQ(reused.image.height, fresh.image.height);
  EXPECT_EQ(reused.image.rgb, fresh.image.rgb);
  EXPECT_EQ(reused.mask, fresh.mask);
  EXPECT_EQ(reused.shadowEdgePixels, fresh.shadowEdgePixels);
  EXPECT_EQ(reused.maskedPixels, fresh.maskedPixels);
  EXPECT_EQ(reused.tiles, fresh.tiles);
  EXPECT_EQ(reused.rays.total(), fresh.rays.total());
  EXPECT_LT(reused.maskedPixels, static_cast<std::size_t>(s.frame.width * s.frame.height));
}

// Every headless OpenGL this build has draws the same hybrid frame, to the
// byte: the marks, the raster's colour, the composed image (the thesis's
// scenes, the glass and the bunny, with shadow maps and traced edges).
TEST(Hybrid, EveryGlBackendDrawsTheSameBytes) {
  const std::vector<gl::GlBackend>& backends = gl::builtGlBackends();
  if (backends.size() < 2) GTEST_SKIP() << "this build has one headless OpenGL";
  for (const char* name : {"scenes/room.json", "scenes/room-gl-floor.json", "scenes/glass.json", "scenes/bunny.json"}) {
    const SceneSetup s = load(name);
    const PreparedScene prepared(s.loaded.scene, BvhSettings{});
    ThreadPool pool(2);
    LocalTileService local(prepared, pool);
    std::vector<HybridResult> results;
    for (const gl::GlBackend backend : backends) {
      gl::OffscreenContext context(s.frame.width, s.frame.height, backend);
      EXPECT_EQ(context.backend(), backend);
      gl::RasterScene raster(context.api(), prepared.scene());
      renderHybrid(context.api(), raster, local, s.frame, prepared.scene().mask, 32, results.emplace_back());
    }
    for (std::size_t i = 1; i < results.size(); ++i) {
      EXPECT_EQ(results[i].mask, results[0].mask) << name << ": " << enumWord(backends[i]);
      EXPECT_EQ(results[i].image.rgb, results[0].image.rgb) << name << ": " << enumWord(backends[i]);
      EXPECT_GT(results[i].maskedPixels, 0u) << name;
    }
  }
}

// Asked for by name, a backend is that one or an error that names it.
TEST(Hybrid, AGlBackendAskedForIsTheOneUsed) {
  for (const gl::GlBackend backend : gl::builtGlBackends()) {
    EXPECT_EQ(gl::OffscreenContext(16, 16, backend).backend(), backend);
  }
  EXPECT_EQ(gl::OffscreenContext(16, 16).backend(), gl::builtGlBackends().front());
}

// The share of pixels where two images differ by at most `tolerance` in
// every channel.
double shareWithin(const FrameImage& a, const FrameImage& b, int tolerance) {
  std::size_t close = 0;
  for (std::size_t i = 0; i < a.rgb.size() / 3; ++i) close += channelDifference(a, b, i) <= tolerance ? 1 : 0;
  return static_cast<double>(close) / static_cast<double>(a.rgb.size() / 3);
}

// The hybrid frame of a scene (its own mask rule, shadow maps at 1024)
// beside the full trace, one sample a pixel.
void expectHybridNearFullTrace(const std::string& json, const char* what) {
  const Scene scene = test::sceneFromJson(json);
  const PreparedScene prepared(scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService service(prepared, pool);
  const FrameImage full = renderFrame(service, scene.frame, {}).image;
  const HybridResult h = hybrid(prepared.scene(), service, scene.frame, rule(scene.mask.rule, 1024));
  const double share = shareWithin(h.image, full, 8);
  std::printf("%s: %.4f of the pixels within 8/255 of the full trace\n", what, share);
  EXPECT_GE(share, 0.99) << what;
}

// Nothing the tracer sees is clipped by the raster: a ground 10 km wide seen
// from 6 m (the far plane is 7 km away) and a room with a sphere 10,000
// units behind it. With the projection's near plane at far / 1000 the first
// lost both spheres and the near ground, and the second the whole room.
TEST(Hybrid, NearGeometryIsDrawnInScenesOfLargeExtent) {
  const std::string lights = R"("lights": [{"type": "point", "position": [3, 8, 4]}],
    "sampling": {"pattern": "regular", "samples": 1, "filter": "box"},
    "materials": {"ground": {"color": [0.6, 0.6, 0.5], "ambient": 0.1, "diffuse": 0.8},
                  "red": {"color": [0.9, 0.2, 0.2], "ambient": 0.1, "diffuse": 0.7, "specular": 0.3, "shininess": 30},
                  "mirror": {"color": [0.8, 0.8, 0.8], "ambient": 0.02, "diffuse": 0.1, "reflectivity": 0.8}},)";
  expectHybridNearFullTrace(R"({"glint": 1, "image": {"width": 160, "height": 120},
    "camera": {"eye": [0, 2, 6], "look_at": [0, 1, 0], "fov_y": 50}, )" +
                                lights + R"(
    "objects": [
      {"type": "quad", "corners": [[-5000, 0, 5000], [5000, 0, 5000], [5000, 0, -5000], [-5000, 0, -5000]],
       "material": "ground"},
      {"type": "sphere", "center": [-1, 1, 0], "radius": 1, "material": "red"},
      {"type": "sphere", "center": [1.5, 0.7, 1], "radius": 0.7, "material": "mirror"}]})",
                            "ground 10 km wide");
  expectHybridNearFullTrace(R"({"glint": 1, "image": {"width": 160, "height": 120},
    "camera": {"eye": [0.3, 1.6, 5.2], "look_at": [0, 1.2, 0], "fov_y": 50}, )" +
                                lights + R"(
    "objects": [
      {"type": "quad", "corners": [[-3, 0, 6], [3, 0, 6], [3, 0, -3], [-3, 0, -3]], "material": "ground"},
      {"type": "quad", "corners": [[-3, 0, -3], [3, 0, -3], [3, 3, -3], [-3, 3, -3]], "material": "ground"},
      {"type": "sphere", "center": [0.9, 0.7, -0.6], "radius": 0.7, "material": "mirror"},
      {"type": "sphere", "center": [-1, 1.2, 0], "radius": 0.5, "material": "red"},
      {"type": "sphere", "center": [0, 0, -10000], "radius": 1, "material": "red"}]})",
                            "room with a sphere 10,000 behind it");
}

// Materials and textures are bounded by memory alone: 300 quads, each with
// a material of its own, 40 of them with checker textures of their own (the
// uniform arrays held 128 and 32), drawn as the tracer's direct light.
TEST(Hybrid, ManyMaterialsAndTextures) {
  std::string materials, textures, objects;
  for (int i = 0; i < 300; ++i) {
    const std::string n = std::to_string(i);
    const double r = 0.2 + 0.7 * (i % 7) / 6.0, g = 0.2 + 0.7 * (i % 5) / 4.0, b = 0.2 + 0.7 * (i % 3) / 2.0;
    if (i < 40) {
      textures += std::string(textures.empty() ? "" : ",") + "\"t" + n +
                  "\": {\"type\": \"checker\", \"scale\": " + std::to_string(2 + i % 5) + ", \"colors\": [[" +
                  std::to_string(r) + ", 0.2, 0.2], [0.1, 0.1, " + std::to_string(b) + "]]}";
    }
    materials +=
        std::string(materials.empty() ? "" : ",") + "\"m" + n + "\": {" +
        (i < 40 ? "\"texture\": \"t" + n + "\""
                : "\"color\": [" + std::to_string(r) + ", " + std::to_string(g) + ", " + std::to_string(b) + "]") +
        ", \"ambient\": 0.1, \"diffuse\": 0.8, \"specular\": " + std::to_string((i % 4) * 0.1) + ", \"shininess\": 20}";
    const double x = -3.0 + 0.3 * (i % 20), y = 0.3 * (i / 20);
    objects += std::string(objects.empty() ? "" : ",") + "{\"type\": \"quad\", \"corners\": [[" + std::to_string(x) +
               ", " + std::to_string(y) + ", 0], [" + std::to_string(x + 0.3) + ", " + std::to_string(y) + ", 0], [" +
               std::to_string(x + 0.3) + ", " + std::to_string(y + 0.3) + ", 0], [" + std::to_string(x) + ", " +
               std::to_string(y + 0.3) + ", 0]], \"material\": \"m" + n + "\"}";
  }
  const Scene scene = test::sceneFromJson(R"({"glint": 1, "image": {"width": 160, "height": 120},
    "camera": {"eye": [0, 2.25, 5], "look_at": [0, 2.25, 0], "fov_y": 60},
    "sampling": {"pattern": "regular", "samples": 1, "filter": "box"},
    "lights": [{"type": "point", "position": [1, 3, 4]}],
    "textures": {)" + textures + R"(}, "materials": {)" +
                                          materials + R"(}, "objects": [)" + objects + "]}");
  ASSERT_EQ(scene.materials.size(), 300u);
  const PreparedScene prepared(scene, BvhSettings{});
  int compared = 0;
  EXPECT_EQ(offByMoreThanTwo(rasterAndDirectTrace(prepared), fullyCovered(prepared, scene.frame), compared), 0);
  EXPECT_GT(compared, static_cast<int>(scene.frame.width * scene.frame.height) / 2);
}

// An image texture's wrap modes and filters read the same in OpenGL as in
// the tracer: a quad whose uvs run from -1.25 to 2.25 (three and a half
// copies of a 4 x 3 image of distinct texels each way), drawn as the
// tracer's direct light within 2/255, under every mode along u and v.
TEST(Hybrid, TextureWrapModesAreTheTracers) {
  FrameImage texels;
  texels.width = 4;
  texels.height = 3;
  for (int i = 0; i < 12; ++i) {
    texels.rgb.insert(texels.rgb.end(), {static_cast<std::uint8_t>(20 * i), static_cast<std::uint8_t>(240 - 15 * i),
                                         static_cast<std::uint8_t>(i % 2 ? 200 : 40)});
  }
  MemorySource files;
  files.add("texels.png", test::pngBytes(texels));
  for (const char* filter : {"nearest", "bilinear"}) {
    std::set<std::size_t> frames;  // each mode reads the image its own way: the frames' hashes
    for (const char* wrap : {"\"repeat\"", "\"mirrored_repeat\"", "\"clamp_to_edge\"",
                             "[\"mirrored_repeat\", \"clamp_to_edge\"]", "[\"clamp_to_edge\", \"repeat\"]"}) {
      SCOPED_TRACE(std::string(filter) + " " + wrap);
      const Scene scene = loadScene(R"({"glint": 1, "image": {"width": 96, "height": 96},
        "camera": {"eye": [0, 0, 2.6], "look_at": [0, 0, 0], "fov_y": 50},
        "lights": [{"type": "point", "position": [0.5, 0.5, 3]}],
        "textures": {"t": {"type": "image", "file": "texels.png", "filter": ")" +
                                        std::string(filter) + R"(", "wrap": )" + wrap + R"(}},
        "materials": {"m": {"texture": "t", "ambient": 0.2, "diffuse": 0.8}},
        "objects": [{"type": "quad", "corners": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]],
                     "uvs": [[-1.25, -1.25], [2.25, -1.25], [2.25, 2.25], [-1.25, 2.25]], "material": "m"}]})",
                                    files);
      const PreparedScene prepared(scene, BvhSettings{});
      const RasterAndTrace r = rasterAndDirectTrace(prepared);
      // Pixels on one triangle throughout; nearest texels also of one colour
      // (a texel's edge falls where the raster's and the tracer's uv may
      // round apart).
      const bool nearest = std::string(filter) == "nearest";
      int compared = 0;
      EXPECT_EQ(offByMoreThanTwo(r, fullyCovered(prepared, scene.frame, 0.45f, nearest), compared), 0);
      EXPECT_GT(compared, scene.frame.width * scene.frame.height / (nearest ? 3 : 2));
      frames.insert(std::hash<std::string_view>{}(
          std::string_view(reinterpret_cast<const char*>(r.traced.rgb.data()), r.traced.rgb.size())));
    }
    EXPECT_EQ(frames.size(), 5u) << filter;
  }
}

// A smooth mesh's terminator: where a triangle's plane turns from a light
// its vertex normals still catch, OpenGL cannot tell whether the triangles
// around block it (the tracer decides, from the point lifted onto the smooth
// surface: ShadowTerminator proves its terminator the analytic sphere's), nor
// read the shadow map from behind the triangle. Those pixels are traced, so
// the hybrid frame is the full trace's within 2/255 where a ball's shadow
// crosses the terminator (left to GL, unshadowed, 30-odd pixels of it were
// lit), for a point light's cube map and a directional light's layer.
TEST(Hybrid, ASmoothMeshsTerminatorIsTheTracers) {
  const MeshInput mesh = test::icosphere(2, glm::vec3(0.0f, 1.0f, 0.0f), 1.0f);
  nlohmann::json positions = nlohmann::json::array(), normals = nlohmann::json::array();
  for (const glm::vec3& p : mesh.positions) {
    const glm::vec3 n = glm::normalize(p - glm::vec3(0.0f, 1.0f, 0.0f));
    positions.insert(positions.end(), {p.x, p.y, p.z});
    normals.insert(normals.end(), {n.x, n.y, n.z});
  }
  for (const char* light : {R"({"type": "point", "position": [5, 3, -1]})",
                            R"({"type": "directional", "direction": [-1, -0.3, 0.25]})"}) {
    nlohmann::json scene = nlohmann::json::parse(R"({"glint": 1, "image": {"width": 160, "height": 120},
      "camera": {"eye": [0, 1.5, 4.5], "look_at": [0, 0.8, 0], "fov_y": 40},
      "materials": {"m": {"color": [0.9, 0.9, 0.9], "ambient": 0.1, "diffuse": 0.9}},
      "objects": [{"type": "quad", "corners": [[-4, 0, 4], [4, 0, 4], [4, 0, -4], [-4, 0, -4]], "material": "m"},
                  {"type": "sphere", "center": [1.6, 1.65, 0.4], "radius": 0.25, "material": "m"}]})");
    scene["lights"] = {nlohmann::json::parse(light)};
    scene["objects"].push_back(
        {{"type", "mesh"}, {"positions", positions}, {"normals", normals}, {"indices", mesh.indices}, {"material", "m"}});
    const Scene loaded = test::sceneFromJson(scene.dump());
    const PreparedScene prepared(loaded, BvhSettings{});
    ThreadPool pool(2);
    LocalTileService service(prepared, pool);
    const FrameImage full = renderFrame(service, loaded.frame, {}).image;
    const HybridResult h = hybrid(prepared.scene(), service, loaded.frame, rule(MaskRule::kAuto, 1024));
    int unlike = 0;
    for (std::size_t i = 0; i < h.mask.size(); ++i) unlike += channelDifference(h.image, full, i) > 2 ? 1 : 0;
    std::printf("%s: %zu pixels traced for their shadows, %d more than 2/255 from the full trace\n", light,
                h.shadowEdgePixels, unlike);
    EXPECT_GT(h.shadowEdgePixels, 100u) << light;
    EXPECT_EQ(unlike, 0) << light;
  }
}

// The raster and the tracer encode the background alike: an empty scene's
// hybrid frame is the full trace's, byte for byte (a background of 0.3 was
// 76 rasterized and 77 traced), linear and sRGB with an exposure.
TEST(Hybrid, BackgroundIsTheTracersToTheByte) {
  const Scene scene = test::sceneFromJson(R"({"glint": 1, "image": {"width": 64, "height": 48},
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, "background": [0.3, 0.5, 0.7], "objects": []})");
  const PreparedScene prepared(scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService service(prepared, pool);
  for (const OutputSettings output : {OutputSettings{Encoding::kLinear, 0.0f}, OutputSettings{Encoding::kSrgb, 0.7f}}) {
    FrameSettings frame = scene.frame;
    frame.output = output;
    const FrameImage full = renderFrame(service, frame, {}).image;
    EXPECT_EQ(full.rgb[0], output.encoding == Encoding::kLinear ? 77 : Encoder(output).byte(0.3f));
    EXPECT_EQ(hybrid(prepared.scene(), service, frame, rule(MaskRule::kNone)).image.rgb, full.rgb);
  }
}

// A hybrid frame hands its tiles to the service in sets (the masked
// objects; the shadow and raster edges): through two glintd the frame's
// report counts them all. The servers' pixels add up to the frame's, and
// the provenance image tints every traced pixel and no other.
TEST(Hybrid, ReportCountsEveryTracedSet) {
  const SceneSetup s = load("scenes/room.json");
  server::BackgroundServer first(quietLoopback(1)), second(quietLoopback(1));
  DistributedTileService remote(resolveServers({first.address(), second.address()}), s.loaded.bundle);
  remote.awaitServers(std::chrono::seconds(10));
  const HybridResult h = hybrid(s.loaded.scene, remote, s.frame, rule(MaskRule::kAuto, 256));
  ASSERT_GT(h.shadowEdgePixels + h.rasterEdgePixels, 0u);
  const DistributionReport& report = remote.lastFrame();
  std::size_t pixels = 0, tiles = 0;
  for (const ServerReport& server : report.servers) {
    pixels += server.maskedPixels;
    tiles += server.tiles;
  }
  EXPECT_EQ(pixels, h.maskedPixels);
  EXPECT_EQ(tiles, static_cast<std::size_t>(h.tiles));
  const FrameImage tinted = provenanceImage(h.image, report);
  std::size_t untinted = 0, changedRaster = 0;
  for (std::size_t i = 0; i < h.mask.size(); ++i) {
    bool changed = false;
    for (std::size_t k = 3 * i; k < 3 * i + 3; ++k) changed = changed || tinted.rgb[k] != h.image.rgb[k];
    if (h.mask[i] == kRasterPixel) {
      changedRaster += changed ? 1 : 0;
    } else {
      untinted += changed ? 0 : 1;
    }
  }
  EXPECT_EQ(changedRaster, 0u);
  EXPECT_LT(untinted, h.maskedPixels / 1000 + 1);  // a pixel already of its server's colour stays as it is
}

}  // namespace
}  // namespace glint
