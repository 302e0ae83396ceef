// The penumbra proof of a block of points at once never clears a point that
// its own proof does not, and clears whole blocks away from the shadows; a
// point whose one ray is blocked is never one its proof clears; a point
// proved against its block's suspects is proved as against every primitive.
#include "client/raster/penumbra_proof.h"

#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint::gl {
namespace {

struct Tally {
  int cleared = 0;   // blocks proved at once
  int refused = 0;   // blocks left to their points
  int shadowed = 0;  // points of refused blocks their own proof does not clear
  int plain = 0;     // points plainly blocked (one ray)
  int suspected = 0;  // points of refused blocks proved against the block's suspects
};

// Blocks of 4 x 4 points a spacing apart on the plane through `centre`
// along unit axes u and v, their corners spread at random over the square of
// half-side `extent` about the centre.
Tally checkBlocks(const PenumbraProof& proof, const glm::vec3& eye, const glm::vec3& centre, const glm::vec3& u,
                  const glm::vec3& v, float extent, float spacing) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> at(-extent, extent);
  Tally t;
  for (int b = 0; b < 300; ++b) {
    const glm::vec3 corner = centre + at(rng) * u + at(rng) * v;
    std::vector<glm::vec3> points;
    for (int k = 0; k < 16; ++k) {
      points.push_back(corner + spacing * (static_cast<float>(k % 4) * u + static_cast<float>(k / 4) * v));
    }
    for (const glm::vec3& p : points) {
      if (!proof.plainlyBlocked(p, eye)) continue;
      ++t.plain;
      EXPECT_FALSE(proof.seesWhole(p, eye)) << p.x << " " << p.y << " " << p.z;
    }
    if (proof.allSeeWhole(points, eye)) {
      ++t.cleared;
      for (const glm::vec3& p : points) EXPECT_TRUE(proof.seesWhole(p, eye)) << p.x << " " << p.z;
      continue;
    }
    ++t.refused;
    const std::optional<std::vector<std::uint32_t>> suspects = proof.suspects(points, eye);
    for (const glm::vec3& p : points) {
      const bool whole = proof.seesWhole(p, eye);
      t.shadowed += whole ? 0 : 1;
      if (suspects) {
        EXPECT_EQ(proof.seesWhole(p, eye, *suspects), whole) << p.x << " " << p.y << " " << p.z;
      }
      t.suspected += suspects && !suspects->empty() ? 1 : 0;
    }
  }
  return t;
}

TEST(PenumbraProof, ABlockClearedAtOnceIsClearedPointByPoint) {
  const Scene scene = loadSceneFile(test::sourcePath("scenes/soft-shadows.json"));
  const PenumbraProof proof(scene, EffectPlan::derive(scene, scene.frame));
  ASSERT_TRUE(proof.active());
  const Tally t = checkBlocks(proof, scene.frame.camera.eye, glm::vec3(0.0f, 0.001f, 0.0f), glm::vec3(1, 0, 0),
                              glm::vec3(0, 0, 1), 4.0f, 0.05f);
  EXPECT_GT(t.cleared, 30);
  EXPECT_GT(t.shadowed, 30);  // blocks in the sphere's and the mesh's shadows
  EXPECT_GT(t.plain, 30);
  EXPECT_GT(t.suspected, 30);
}

// The Cornell box's emitting square as lights (path transport's light drawn
// from an irradiance field): the same on its back wall, above and beside the
// tall box.
TEST(PenumbraProof, ABlockClearedAtOnceIsClearedPointByPointUnderAnEmitter) {
  const Scene scene = loadSceneFile(test::sourcePath("scenes/cornell.json"));
  const EffectPlan plan = EffectPlan::derive(scene, scene.frame);
  PenumbraProof proof(scene, plan);
  const std::optional<EmitterPatches> patches = EmitterPatches::of(scene, plan, 0);
  ASSERT_TRUE(patches);
  proof.addEmitters(*patches);
  ASSERT_TRUE(proof.active());
  const Bounds3 box = scene.geometry.bounds();
  const float extent = 0.45f * (box.max.x - box.min.x);
  const glm::vec3 back(box.centre().x, box.centre().y, box.max.z - 0.001f * extent);
  const Tally t =
      checkBlocks(proof, scene.frame.camera.eye, back, glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), extent, 0.02f * extent);
  EXPECT_GT(t.cleared, 30);
  EXPECT_GT(t.shadowed, 30);
  EXPECT_GT(t.plain, 30);
  EXPECT_GT(t.suspected, 30);
}

}  // namespace
}  // namespace glint::gl
