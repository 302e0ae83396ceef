#include "tests/bench/embree_section.h"

#include <cstdio>

#if GLINT_BENCH_EMBREE

#include <cmath>
#include <random>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include "common/bvh.h"
#include "common/camera.h"
#include "common/timing.h"
#include "tests/bench/bench_scenes.h"

namespace glint::bench {
namespace {

// The geometry's triangles as one Embree scene (its own copy of the
// vertices and indices).
RTCScene embreeScene(RTCDevice device, const Geometry& g) {
  RTCScene scene = rtcNewScene(device);
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
  rtcCommitGeometry(mesh);
  rtcAttachGeometry(scene, mesh);
  rtcReleaseGeometry(mesh);
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

// Primary rays of a width x height view over the terrain, and from each
// primary hit one ray in a random direction of the upper half-space.
void makeRays(const Bvh& bvh, int width, int height, std::vector<Ray>& primary, std::vector<Ray>& incoherent) {
  const Camera camera({{0.0f, 25.0f, 60.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 50.0f}, width, height);
  std::mt19937 rng(7);
  std::normal_distribution<float> n;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      primary.push_back(camera.generateRay({x + 0.5f, y + 0.5f}));
      const auto hit = bvh.intersect(primary.back(), 1e30f);
      if (!hit) continue;
      glm::vec3 d = glm::normalize(glm::vec3(n(rng), std::abs(n(rng)), n(rng)));
      incoherent.emplace_back(primary.back().o + primary.back().d * (hit->t * 0.999f), d);
    }
  }
}

struct Traced {
  double glintMs = 0.0;
  double embreeMs = 0.0;
  double agree = 0.0;  // share of rays where both hit at t within 1e-4 relative, or both miss
};

Traced trace(const Bvh& bvh, RTCScene scene, const std::vector<Ray>& rays, int runs) {
  Traced r;
  std::vector<float> glintT(rays.size()), embreeT(rays.size());
  r.glintMs = medianMs(runs, [&] {
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const auto hit = bvh.intersect(rays[i], 1e30f);
      glintT[i] = hit ? hit->t : -1.0f;
    }
  });
  r.embreeMs = medianMs(runs, [&] {
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

}  // namespace

void embreeSection(bool quick, int runs) {
  const Geometry g = terrain(quick ? 100 : 1000, quick ? 50 : 500);
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = nullptr;
  const double embreeBuildMs = medianMs(runs, [&] {
    if (scene) rtcReleaseScene(scene);
    scene = embreeScene(device, g);
    rtcCommitScene(scene);
  });
  Bvh bvh;
  const double glintBuildMs = medianMs(runs, [&] { bvh = Bvh::build(g, BvhSettings{}); });
  std::vector<Ray> primary, incoherent;
  makeRays(bvh, quick ? 128 : 1024, quick ? 96 : 768, primary, incoherent);
  const Traced p = trace(bvh, scene, primary, runs), s = trace(bvh, scene, incoherent, runs);
  const auto mrays = [](std::size_t n, double ms) { return static_cast<double>(n) / ms / 1e3; };
  std::printf("\n## Glint beside Embree %d.%d.%d: %u triangles, median of %d\n\n", RTC_VERSION_MAJOR,
              RTC_VERSION_MINOR, RTC_VERSION_PATCH, g.primitiveCount(), runs);
  std::printf("| measure | Glint | Embree | Glint / Embree | rays agreeing |\n|---|---:|---:|---:|---:|\n");
  std::printf("| build ms (SAH, every thread; Embree's includes copying the mesh) | %.0f | %.0f | %.2fx time | |\n",
              glintBuildMs, embreeBuildMs, glintBuildMs / embreeBuildMs);
  std::printf("| primary rays, Mrays/s, 1 thread (%zu) | %.2f | %.2f | %.2fx speed | %.4f |\n", primary.size(),
              mrays(primary.size(), p.glintMs), mrays(primary.size(), p.embreeMs), p.embreeMs / p.glintMs, p.agree);
  std::printf("| incoherent rays, Mrays/s, 1 thread (%zu) | %.2f | %.2f | %.2fx speed | %.4f |\n", incoherent.size(),
              mrays(incoherent.size(), s.glintMs), mrays(incoherent.size(), s.embreeMs), s.embreeMs / s.glintMs,
              s.agree);
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
}

}  // namespace glint::bench

#else

namespace glint::bench {

void embreeSection(bool, int) {
  std::printf("\n## Glint beside Embree: skipped, libembree-dev is not installed (make bench installs it)\n");
}

}  // namespace glint::bench

#endif
