#include "client/commands/info_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include <glm/trigonometric.hpp>

#include "client/raster/hybrid_frame.h"
#include "client/raster/offscreen_context.h"
#include "client/raster/pixel_mark.h"
#include "client/raster/raster_scene.h"
#include "client/commands/scene_warnings.h"
#include "common/render/effects.h"
#include "common/render/field_probes.h"
#include "common/render/mask_rule.h"
#include "common/render/path_tracer.h"
#include "common/scene/load_limits.h"
#include "common/scene/scene_load.h"

namespace glint {
namespace {

std::string scalar(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::string vec(const glm::vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", v.x, v.y, v.z);
  return text;
}

// "1 mesh", "2 meshes".
std::string count(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// A cone's half-angle from its cosine: "30 deg".
std::string formatDegrees(float cosine) {
  char text[32];
  std::snprintf(text, sizeof text, "%g deg", glm::degrees(std::acos(std::clamp(cosine, -1.0f, 1.0f))));
  return text;
}

std::string percent(std::size_t part, std::size_t whole) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f %%",
                whole ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0);
  return text;
}

// Under path transport, whether the hybrid frame draws the light between
// surfaces from an irradiance field (applyFrameOverrides left the rule
// other than all only where it can).
bool drawsField(const Scene& scene) {
  return scene.frame.tracing.transport == Transport::kPath && scene.mask.rule != MaskRule::kAll;
}

void printFrame(const Scene& scene) {
  const FrameSettings& f = scene.frame;
  std::printf("  image      %dx%d, %d %s samples a pixel, %s filter\n", f.width, f.height, f.sampling.samples,
              std::string(enumWord(f.sampling.pattern)).c_str(), std::string(enumWord(f.sampling.filter)).c_str());
  if (f.tracing.transport == Transport::kPath) {
    const std::string where =
        drawsField(scene) ? "the hybrid frame draws it from an irradiance field (" +
                                std::to_string(f.tracing.field->probes) + " probes along the longest side, " +
                                std::to_string(f.tracing.field->rays) + " rays each) and traces what it cannot decide"
                          : std::string("every pixel traced");
    std::printf("  transport  path: light between surfaces too, up to %d bounces after the first hit, Russian "
                "roulette after %d; %s\n",
                f.tracing.maxBounces, PathTracer::kRouletteFrom, where.c_str());
  } else {
    std::printf("  transport  whitted: direct light, mirror and refracted rays to max depth %d, min weight %g; "
                "ambient for the rest\n",
                f.tracing.maxDepth, f.tracing.minWeight);
  }
  const CameraSpec& c = f.camera;
  std::printf("  camera     eye %s, look_at %s, up %s, fov_y %g\n", vec(c.eye).c_str(), vec(c.lookAt).c_str(),
              vec(c.up).c_str(), c.fovY);
}

void printBounds(const Scene& scene) {
  const Bounds3 b = scene.geometry.bounds();
  if (b.empty()) {
    std::printf("  bounds     none (no object)\n");
    return;
  }
  const FrameSettings& f = scene.frame;
  const CameraSpec fit = fitCamera(f.camera, b, static_cast<float>(f.width) / static_cast<float>(f.height));
  std::printf("  bounds     min %s, max %s, size %s, centre %s\n", vec(b.min).c_str(), vec(b.max).c_str(),
              vec(b.extent()).c_str(), vec(b.centre()).c_str());
  std::printf("  fit        eye %s, look_at %s (camera \"fit\": true, or --fit)\n", vec(fit.eye).c_str(),
              vec(fit.lookAt).c_str());
}
// One light, as the scene gives it.
std::string describeLight(const Light& l) {
  const std::string kind(enumWord(l.type));
  const std::string light = "colour " + vec(l.color);
  const std::string falloff = ", attenuation " + vec(l.attenuation);
  switch (l.type) {
    case LightType::kDirectional:
      return kind + " along " + vec(l.direction) + ", " + light;
    case LightType::kSpot:
      return kind + " at " + vec(l.position) + " along " + vec(l.direction) + ", cones " +
             formatDegrees(l.cosInner) + " and " + formatDegrees(l.cosOuter) + ", " + light + falloff;
    case LightType::kArea:
      return kind + " at " + vec(l.position) + ", edges " + vec(l.u) + " " + vec(l.v) + ", " +
             std::to_string(l.samples) + " samples, " + light + falloff;
    case LightType::kSphere:
      return kind + " at " + vec(l.position) + ", radius " + scalar(l.radius) + ", " + std::to_string(l.samples) +
             " samples, " + light + falloff;
    case LightType::kPoint:
      break;
  }
  return kind + " at " + vec(l.position) + ", " + light + falloff;
}


// The surfaces that emit light, and whether they light the others (path
// transport) or only show their own colour (Whitted's).
std::string emitting(const Scene& scene) {
  const Geometry& g = scene.geometry;
  const EffectPlan plan = EffectPlan::derive(scene);
  std::size_t count = 0;
  for (std::uint32_t prim = 0; prim < g.primitiveCount(); ++prim) count += plan.materials[g.materialOf(prim)].emits;
  if (count == 0) return "";
  const bool lights = scene.frame.tracing.transport == Transport::kPath;
  return "; " + std::to_string(count) + (count == 1 ? " emitting surface" : " emitting surfaces") +
         (lights ? " (lighting the others: path transport)" : " (their own colour only: Whitted transport)");
}

void printContents(const Scene& scene) {
  const Geometry& g = scene.geometry;
  std::printf("  objects    %s, %s; %s (%zu dropped: cannot be hit), %s\n",
              count(g.models().size(), "mesh", "meshes").c_str(),
              count(g.spheres().size(), "sphere", "spheres").c_str(),
              count(g.triangles().size(), "triangle", "triangles").c_str(), g.droppedTriangles(),
              count(g.positions().size(), "vertex", "vertices").c_str());
  std::size_t traced = 0;
  std::string names;
  for (const Material& m : scene.materials) {
    if (!materialMasked(m, scene.mask)) continue;
    names += (traced++ ? ", " : ": ") + (m.name.empty() ? std::string("(unnamed)") : m.name);
  }
  std::printf("  materials  %zu, %zu traced under the mask rule %s%s\n", scene.materials.size(), traced,
              std::string(enumWord(scene.mask.rule)).c_str(), names.c_str());
  std::size_t images = 0, checkers = 0;
  for (const Texture& t : scene.textures) {
    images += t.type == TextureType::kImage ? 1 : 0;
    checkers += t.type == TextureType::kChecker ? 1 : 0;
  }
  std::printf("  textures   %zu (%s, %s)\n", scene.textures.size(), count(images, "image", "images").c_str(),
              count(checkers, "checker", "checkers").c_str());
  std::printf("  lights     %s%s\n", count(scene.lights.size(), "light", "lights").c_str(), emitting(scene).c_str());
  for (const Light& l : scene.lights) std::printf("             %s\n", describeLight(l).c_str());
  if (const Environment* e = scene.environment.get()) {
    std::printf("  sky        %dx%d environment image (escaping rays; the background %s)\n", e->width, e->height,
                backgroundMasked(scene, scene.mask) ? "traced" : "drawn flat by OpenGL");
  }
}

// The effect plan: what the tracer simulates, what it leaves out.
void printPlan(const Scene& scene) {
  const EffectPlan plan = EffectPlan::derive(scene);
  std::string on, off;
  for (const NamedEffect& e : namedEffects(plan)) (e.needed ? on : off).append(" ").append(e.name);
  std::printf("  effects    simulated:%s; left out:%s\n", on.empty() ? " none" : on.c_str(),
              off.empty() ? " none" : off.c_str());
  std::printf("  raster     %s\n", rasterShadows(scene, plan, scene.mask)
                                       ? "shadow maps drawn (they decide which raster pixels are lit)"
                                       : "no shadow maps needed");
}

// One raster pass: the pixels the hybrid frame would trace, and why.
void printHybrid(const Scene& scene, int tileSize, std::optional<gl::GlBackend> backend) {
  const FrameSettings& f = scene.frame;
  const std::size_t pixels = static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height);
  if (scene.mask.rule == MaskRule::kAll) {
    std::printf("  hybrid     mask rule all: every pixel traced (%zu)\n", pixels);
    return;
  }
  std::optional<IrradianceField> field;  // filled as glint render fills it: its marks depend on it
  gl::OffscreenContext context(f.width, f.height, backend);
  gl::RasterScene raster(context.api(), scene);
  if (drawsField(scene)) {
    const PreparedScene prepared(scene, BvhSettings{});
    RayStats rays;
    field.emplace(buildField(prepared, f, *f.tracing.field, rays));
    raster.useField(*field);
  }
  HybridResult r;
  markHybrid(context.api(), raster, f, scene.mask, tileSize, r);
  std::size_t marked[4] = {0, 0, 0, 0};  // by PixelMark
  for (const std::uint8_t mark : r.mask) ++marked[markOf(mark)];
  std::printf(
      "  hybrid     traces %zu of %zu pixels (%s) in %d tiles of %d: %zu of masked objects, %zu of "
      "undecided shadows, %zu on the raster's edges (raster pass %.1f ms)\n",
      r.maskedPixels, pixels, percent(r.maskedPixels, pixels).c_str(), r.tiles, tileSize, marked[kMaskedPixel],
      marked[kShadowEdgePixel], marked[kRasterEdgePixel], r.times.totalMs);
  std::printf("             (OpenGL: %s)\n", std::string(enumWord(context.backend())).c_str());
}

}  // namespace

void runInfo(const InfoOptions& options) {
  Scene scene = loadSceneFile(options.scene);
  printSceneWarnings(options.scene, scene);
  printNote(applyFrameOverrides(options.frame, scene));
  std::printf("%s\n", options.scene.c_str());
  printFrame(scene);
  printBounds(scene);
  printContents(scene);
  printPlan(scene);
  if (options.raster) printHybrid(scene, options.frame.tileSize, options.gl);
}

}  // namespace glint
