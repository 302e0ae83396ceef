#include "tests/bench/embree_section.h"

#include <cstdio>

#if GLINT_BENCH_EMBREE

#include <cmath>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include "common/geometry/bvh.h"
#include "common/scene/camera.h"
#include "common/render/optics.h"
#include "common/scene/scene_load.h"
#include "common/base/timing.h"
#include "tests/bench/bench_timing.h"
#include "tests/bench/bench_scenes.h"

namespace glint::bench {
namespace {

// The geometry's triangles as one Embree geometry (its own copy of the
// vertices and indices).
RTCGeometry embreeTriangles(RTCDevice device, const Geometry& g) {
  RTCGeometry mesh = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), g.positions().size()));
  for (std::size_t i = 0; i < g.positions().size(); ++i) {
    for (int k = 0; k < 3; ++k) vertices[3 * i + static_cast<std::size_t>(k)] = g.positions()[i][k];
  }
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), g.triangles().size()));
  for (std::size_t t = 0; t < g.triangles().size(); ++t) {
    for (int k = 0; k < 3; ++k) indices[3 * t + static_cast<std::size_t>(k)] = g.triangles()[t].v[static_cast<std::size_t>(k)];
  }
  return mesh;
}

// The geometry's spheres as Embree's sphere points (centre and radius).
RTCGeometry embreeSpheres(RTCDevice device, const Geometry& g) {
  RTCGeometry points = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(points, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                               4 * sizeof(float), g.spheres().size()));
  for (std::size_t i = 0; i < g.spheres().size(); ++i) {
    const Sphere& sphere = g.spheres()[i];
    for (int k = 0; k < 3; ++k) vertices[4 * i + static_cast<std::size_t>(k)] = sphere.centre[k];
    vertices[4 * i + 3] = sphere.radius;
  }
  return points;
}

// The geometry as one Embree scene, not yet committed.
RTCScene embreeScene(RTCDevice device, const Geometry& g) {
  RTCScene scene = rtcNewScene(device);
  for (RTCGeometry geometry : {g.triangles().empty() ? nullptr : embreeTriangles(device, g),
                               g.spheres().empty() ? nullptr : embreeSpheres(device, g)}) {
    if (!geometry) continue;
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
  }
  return scene;
}

float embreeHit(RTCScene scene, const Ray& ray) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = ray.o.x;
  rh.ray.org_y = ray.o.y;
  rh.ray.org_z = ray.o.z;
  rh.ray.dir_x = ray.d.x;
  rh.ray.dir_y = ray.d.y;
  rh.ray.dir_z = ray.d.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = 1e30f;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &context, &rh);
  return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1.0f : rh.ray.tfar;
}

// One scene of the comparison: its geometry and the view its primary rays
// come from. From each primary hit one ray leaves in a random direction:
// of the upper half-space over the terrain (a height field: below it is
// nothing), of the whole sphere elsewhere.
struct PeerCase {
  std::string name;
  const Geometry& geometry;
  Camera camera;
  int width;
  int height;
  bool upward;
};

// The ray sets traced by both: primary rays (one through each pixel's
// centre), the mirror bounces that follow them, and one ray in a random
// direction from each primary hit.
struct RaySets {
  std::vector<Ray> primary;
  std::vector<Ray> mirror;
  std::vector<Ray> random;
};

// Mirror bounces are followed to the depth of the thesis's room
// (`max_depth` 5: the primary ray and four bounces).
constexpr int kMirrorDepth = 5;

// Appends the bounces of a perfect mirror after `ray`'s hit, as
// Tracer::trace casts them: from the hit's outside origin, in the mirror
// direction, until one escapes or the depth is reached.
void addMirrorBounces(const Bvh& bvh, const Geometry& g, Ray ray, std::optional<Hit> hit, std::vector<Ray>& out) {
  for (int depth = 2; depth <= kMirrorDepth && hit; ++depth) {
    const SurfaceHit s = g.surface(ray, *hit, false);
    ray = Ray(offsetRayOrigin(s.p, s.error, s.ng), mirrorDirection(ray.d, s.ns, s.ng));
    out.push_back(ray);
    hit = bvh.intersect(ray, 1e30f);
  }
}

RaySets makeRays(const Bvh& bvh, const PeerCase& c) {
  RaySets rays;
  std::mt19937 rng(7);
  std::normal_distribution<float> n;
  for (int y = 0; y < c.height; ++y) {
    for (int x = 0; x < c.width; ++x) {
      const Ray& primary = rays.primary.emplace_back(c.camera.generateRay({x + 0.5f, y + 0.5f}));
      const auto hit = bvh.intersect(primary, 1e30f);
      if (!hit) continue;
      addMirrorBounces(bvh, c.geometry, primary, hit, rays.mirror);
      const float ny = n(rng);
      glm::vec3 d = glm::normalize(glm::vec3(n(rng), c.upward ? std::abs(ny) : ny, n(rng)));
      rays.random.emplace_back(primary.o + primary.d * (hit->t * 0.999f), d);
    }
  }
  return rays;
}

// Glint's and Embree's median times of the same work, and the median over
// the runs of Glint's time divided by Embree's in that run.
struct Paired {
  double glintMs = 0.0;
  double embreeMs = 0.0;
  double glintOverEmbree = 0.0;
};

// Runs glint and embree alternately, `runs` times each. The ratio of each
// pair is taken first: this host drifts between fast and slow spells of
// seconds, which move two medians measured one after the other apart
// (Embree's own rate moved by up to 18 % between sections) but a pair
// measured side by side far less.
Paired pairedMs(int runs, const std::function<void()>& glint, const std::function<void()>& embree) {
  std::vector<double> glintMs, embreeMs, ratios;
  for (int i = 0; i < runs; ++i) {
    glintMs.push_back(medianMs(1, glint));
    embreeMs.push_back(medianMs(1, embree));
    ratios.push_back(glintMs.back() / embreeMs.back());
  }
  return {median(glintMs), median(embreeMs), median(ratios)};
}

struct Traced {
  Paired ms;
  double agree = 0.0;  // share of rays where both hit at t within 1e-4 relative, or both miss
};

Traced trace(const Bvh& bvh, RTCScene scene, const std::vector<Ray>& rays, int runs) {
  Traced r;
  std::vector<float> glintT(rays.size()), embreeT(rays.size());
  r.ms = pairedMs(
      runs,
      [&] {
        for (std::size_t i = 0; i < rays.size(); ++i) {
          const auto hit = bvh.intersect(rays[i], 1e30f);
          glintT[i] = hit ? hit->t : -1.0f;
        }
      },
      [&] {
        for (std::size_t i = 0; i < rays.size(); ++i) embreeT[i] = embreeHit(scene, rays[i]);
      });
  std::size_t same = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    same += (glintT[i] < 0.0f) == (embreeT[i] < 0.0f) && std::abs(glintT[i] - embreeT[i]) <= 1e-4f * std::abs(glintT[i])
                ? 1
                : 0;
  }
  r.agree = static_cast<double>(same) / static_cast<double>(rays.size());
  return r;
}

// One row of rays traced: both rates, Glint's as a share of Embree's, and
// how often the two agree.
void printTraced(const std::string& scene, const char* rays, const std::vector<Ray>& set, const Traced& t) {
  const auto mrays = [&](double ms) { return static_cast<double>(set.size()) / ms / 1e3; };
  std::printf("| %s | %s, Mrays/s, 1 thread (%zu) | %.2f | %.2f | %.2fx speed | %.4f |\n", scene.c_str(), rays,
              set.size(), mrays(t.ms.glintMs), mrays(t.ms.embreeMs), 1.0 / t.ms.glintOverEmbree, t.agree);
}

// Builds both trees of one case and traces its three ray sets: the case's rows.
void compare(RTCDevice device, const PeerCase& c, int runs) {
  RTCScene scene = nullptr;
  Bvh bvh;
  const Paired build = pairedMs(
      runs, [&] { bvh = Bvh::build(c.geometry, BvhSettings{}); },
      [&] {
        if (scene) rtcReleaseScene(scene);
        scene = embreeScene(device, c.geometry);
        rtcCommitScene(scene);
      });
  const RaySets rays = makeRays(bvh, c);
  std::printf("| %s | build ms (SAH, every thread; Embree's includes copying the mesh) | %.3g | %.3g | %.2fx time | |\n",
              c.name.c_str(), build.glintMs, build.embreeMs, build.glintOverEmbree);
  printTraced(c.name, "primary rays", rays.primary, trace(bvh, scene, rays.primary, runs));
  printTraced(c.name, "mirror bounces (incoherent: as Glint's reflections)", rays.mirror,
              trace(bvh, scene, rays.mirror, runs));
  printTraced(c.name, "random directions (incoherent: diffuse)", rays.random, trace(bvh, scene, rays.random, runs));
  rtcReleaseScene(scene);
}

// A scene file's geometry and view, at its own image size (quick: a quarter).
PeerCase sceneCase(const std::string& name, const Scene& scene, bool quick) {
  const int width = quick ? scene.frame.width / 4 : scene.frame.width;
  const int height = quick ? scene.frame.height / 4 : scene.frame.height;
  return {name, scene.geometry, Camera(scene.frame.camera, width, height), width, height, false};
}

}  // namespace

void embreeSection(const std::string& scenes, bool quick, int runs) {
  const Geometry terrainGeometry = terrain(quick ? 100 : 1000, quick ? 50 : 500);
  const int width = quick ? 128 : 1024, height = quick ? 96 : 768;
  const Camera terrainView({{0.0f, 25.0f, 60.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 50.0f}, width, height);
  const PeerCase terrainCase{"terrain (" + std::to_string(terrainGeometry.primitiveCount()) + " triangles)",
                             terrainGeometry, terrainView, width, height, true};
  // The closed mesh, seen from inside: every mirror bounce hits it.
  Geometry sphereGeometry;
  sphereGeometry.addMesh(rippledSphere(quick ? 100 : 700));
  const Camera insideView({{0.0f, 0.3f, 0.4f}, {0.0f, 0.0f, -1.0f}, {0.0f, 1.0f, 0.0f}, 60.0f}, width, height);
  const PeerCase sphereCase{"rippled sphere, inside (" + std::to_string(sphereGeometry.primitiveCount()) +
                                " triangles)",
                            sphereGeometry, insideView, width, height, false};
  const Scene bunny = loadSceneFile(std::filesystem::path(scenes) / "bunny.json");
  const Scene room = loadSceneFile(std::filesystem::path(scenes) / "room.json");
  const PeerCase cases[] = {terrainCase, sphereCase, sceneCase("bunny", bunny, quick), sceneCase("room", room, quick)};
  std::printf("\n## Glint beside Embree %d.%d.%d: the same rays, median of %d, the two run alternately (the ratio: "
              "the median of each pair's)\n\n",
              RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH, runs);
  std::printf("| scene | measure | Glint | Embree | Glint / Embree | rays agreeing |\n|---|---|---:|---:|---:|---:|\n");
  RTCDevice device = rtcNewDevice(nullptr);
  for (const PeerCase& c : cases) compare(device, c, runs);
  rtcReleaseDevice(device);
}

}  // namespace glint::bench

#else

namespace glint::bench {

void embreeSection(const std::string&, bool, int) {
  std::printf("\n## Glint beside Embree: skipped, libembree-dev is not installed (make bench installs it)\n");
}

}  // namespace glint::bench

#endif
