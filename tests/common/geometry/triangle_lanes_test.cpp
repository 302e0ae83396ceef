// The block leaf's test (common/geometry/triangle_lanes.h) against the scalar
// watertight test, lane by lane: four lanes per instruction and, where the
// CPU has AVX2, eight; for every lane the same sheared vertices bit for bit,
// and the same hit or miss, with the same bits, as intersectTriangle gives.
#include "common/geometry/triangle_lanes.h"

#include <cstring>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/math/float_bits.h"

namespace glint {
namespace {

bool sameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool sameHit(const std::optional<TriangleHit>& a, const std::optional<TriangleHit>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || std::memcmp(&*a, &*b, sizeof(TriangleHit)) == 0;
}

bool sameShear(const ShearedTriangle& a, const ShearedTriangle& b) {
  return sameBits(a.a, b.a) && sameBits(a.b, b.b) && sameBits(a.c, b.c);
}

// Lane `lane` of a block as the test of V lanes at a time sees it: tested
// for limits up to `bound`, finished with tMax.
struct LaneResult {
  ShearedTriangle sheared;
  std::optional<TriangleHit> hit;
};

template <typename V>
[[gnu::always_inline]] inline LaneResult testLane(const TriangleLanes& block, int lane, const Ray& ray,
                                                  const WatertightRay& w, float bound, float tMax) {
  const int first = lane - lane % kLanesOf<V>;
  TriangleHits<V> hits;
  intersectTriangles(block, first, ray, w, (1u << kLanesOf<V>) - 1u, bound, hits);
  return {hits.sheared.lane(lane - first), hits.lane(lane - first, w, tMax)};
}

#if defined(__x86_64__)
GLINT_AVX2 LaneResult testLaneEight(const TriangleLanes& block, int lane, const Ray& ray, const WatertightRay& w,
                                    float bound, float tMax) {
  return testLane<Float8>(block, lane, ray, w, bound, tMax);
}
#endif

// The lane tests of `lane`: four lanes at a time and, where this CPU has
// AVX2, eight.
std::vector<LaneResult> laneTests(const TriangleLanes& block, int lane, const Ray& ray, const WatertightRay& w,
                                  float bound, float tMax) {
  std::vector<LaneResult> results{testLane<Float4>(block, lane, ray, w, bound, tMax)};
#if defined(__x86_64__)
  if (avx2Available()) results.push_back(testLaneEight(block, lane, ray, w, bound, tMax));
#endif
  return results;
}

// Every lane of every block of kBlockTriangles consecutive triangles against
// every ray, tested for limits up to `bound`, hits up to tMax. Returns how
// many (ray, triangle) pairs hit.
int expectLanesEqualScalar(const std::vector<glm::vec3>& vertices, const std::vector<Ray>& rays, float bound,
                           float tMax) {
  constexpr std::size_t kBlockVertices = 3 * kBlockTriangles;
  int hitCount = 0, mismatches = 0;
  for (std::size_t first = 0; first + kBlockVertices <= vertices.size(); first += kBlockVertices) {
    TriangleLanes block;
    for (int lane = 0; lane < kBlockTriangles; ++lane) {
      block.set(lane, vertices[first + 3 * lane], vertices[first + 3 * lane + 1], vertices[first + 3 * lane + 2]);
    }
    for (const Ray& ray : rays) {
      const WatertightRay w(ray);
      for (int lane = 0; lane < kBlockTriangles; ++lane) {
        const glm::vec3& p0 = vertices[first + 3 * lane];
        const glm::vec3& p1 = vertices[first + 3 * lane + 1];
        const glm::vec3& p2 = vertices[first + 3 * lane + 2];
        const ShearedTriangle expected = shearTriangle(ray, w, p0, p1, p2);
        const std::optional<TriangleHit> scalar = intersectTriangle(ray, w, p0, p1, p2, tMax);
        hitCount += scalar ? 1 : 0;
        for (const LaneResult& got : laneTests(block, lane, ray, w, bound, tMax)) {
          const bool shearSame = sameShear(got.sheared, expected);
          if ((!shearSame || !sameHit(scalar, got.hit)) && mismatches++ < 5) {
            ADD_FAILURE() << "triangle " << first / 3 + lane << ": shear " << (shearSame ? "same" : "differs")
                          << ", scalar " << (scalar ? "hit" : "miss") << ", lanes " << (got.hit ? "hit" : "miss");
          }
        }
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
  return hitCount;
}

TEST(TriangleLanes, RandomTrianglesAndRaysEqualTheScalarTest) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<glm::vec3> vertices;
  for (int i = 0; i < 3 * 64; ++i) vertices.emplace_back(u(rng), u(rng), u(rng));
  std::vector<Ray> rays;
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 o(3.0f * u(rng), 3.0f * u(rng), 3.0f * u(rng));
    rays.emplace_back(o, glm::normalize(glm::vec3(0.3f * u(rng), 0.3f * u(rng), 0.3f * u(rng)) - o));
  }
  const int unbounded = expectLanesEqualScalar(vertices, rays, kInfinity, kInfinity);
  EXPECT_GT(unbounded, 1000);
  // Limited: some hits lie beyond 3.5, and are rejected by both, whether the
  // lane test knew the limit (traversal's bound) or only the finish did.
  const int bounded = expectLanesEqualScalar(vertices, rays, 3.5f, 3.5f);
  EXPECT_GT(bounded, 100);
  EXPECT_LT(bounded, unbounded);
  EXPECT_EQ(expectLanesEqualScalar(vertices, rays, kInfinity, 3.5f), bounded);
  EXPECT_EQ(expectLanesEqualScalar(vertices, rays, 5.0f, 3.5f), bounded);
}

// The hard lanes: rays through shared edges and vertices (edge functions
// exactly zero, recomputed in double), degenerate triangles (zero area, a
// repeated vertex, a point), axis-parallel rays, rays from next to a
// triangle (hits rejected by the error bound of t), far from the origin.
TEST(TriangleLanes, EdgesVerticesAndDegenerateTrianglesEqualTheScalarTest) {
  for (const glm::vec3 offset : {glm::vec3(0.0f), glm::vec3(1e5f, -3e4f, 2e5f)}) {
    const glm::vec3 o = offset;
    const std::vector<glm::vec3> vertices = {
        o + glm::vec3(0, 0, 0), o + glm::vec3(1, 0, 0), o + glm::vec3(1, 1, 0),    // a square's two halves
        o + glm::vec3(0, 0, 0), o + glm::vec3(1, 1, 0), o + glm::vec3(0, 1, 0),    // sharing the diagonal
        o + glm::vec3(0, 0, 0), o + glm::vec3(0, 0, 0), o + glm::vec3(1, 1, 0),    // a repeated vertex
        o + glm::vec3(0, 0, 0), o + glm::vec3(0.5f, 0.5f, 0), o + glm::vec3(1, 1, 0),  // zero area
        o + glm::vec3(0.5f, 0.5f, 0), o + glm::vec3(0.5f, 0.5f, 0), o + glm::vec3(0.5f, 0.5f, 0),  // a point
        o + glm::vec3(0, 0, 1), o + glm::vec3(1, 0, 1), o + glm::vec3(0, 1, 1),
        o + glm::vec3(0, 0, -1), o + glm::vec3(0, 1, -1), o + glm::vec3(1, 1, -1),
        o + glm::vec3(0, 0, 0), o + glm::vec3(0, 1, 0), o + glm::vec3(0, 1, 1),  // edge-on to z rays
    };
    std::vector<Ray> rays;
    for (int i = 0; i <= 16; ++i) {
      for (int j = 0; j <= 16; ++j) {
        const glm::vec3 target = o + glm::vec3(i / 16.0f, j / 16.0f, 0.0f);  // grid points: on edges and vertices
        rays.emplace_back(target + glm::vec3(0, 0, 5), glm::vec3(0, 0, -1));
        rays.emplace_back(target + glm::vec3(3, 2, 5), glm::normalize(glm::vec3(-3, -2, -5)));
        rays.emplace_back(target + glm::vec3(-4, 0, 0.5f), glm::normalize(glm::vec3(4, 0, -0.5f)));
        // Starting a hair above the plane z = 0: hits within their error bound.
        rays.emplace_back(target + glm::vec3(0, 0, 1e-6f), glm::normalize(glm::vec3(0.1f, 0.2f, -1)));
      }
    }
    EXPECT_GT(expectLanesEqualScalar(vertices, rays, kInfinity, kInfinity), 100);
    EXPECT_GT(expectLanesEqualScalar(vertices, rays, 5.0f, 5.0f), 0);
    EXPECT_GT(expectLanesEqualScalar(vertices, rays, kInfinity, 5.0f), 0);
  }
}

}  // namespace
}  // namespace glint
