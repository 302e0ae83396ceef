#include "common/render/mask_rule.h"

#include <gtest/gtest.h>

#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

TEST(MaskRule, AutoFollowsReflectivityTransparencyAndRaytrace) {
  const MaskSettings automatic{MaskRule::kAuto, 0.2f, 0.0f, 0};
  Material m;
  EXPECT_FALSE(materialMasked(m, automatic));
  m.reflectivity = 0.2f;
  EXPECT_FALSE(materialMasked(m, automatic));  // strictly above the threshold
  m.reflectivity = 0.25f;
  EXPECT_TRUE(materialMasked(m, automatic));
  m.raytrace = RaytraceRule::kNever;
  EXPECT_FALSE(materialMasked(m, automatic));
  Material glass;
  glass.transparency = 0.01f;
  EXPECT_TRUE(materialMasked(glass, automatic));
  Material forced;
  forced.raytrace = RaytraceRule::kAlways;
  EXPECT_TRUE(materialMasked(forced, automatic));
  EXPECT_TRUE(materialMasked(Material{}, {MaskRule::kAll, 0.2f, 0.0f, 0}));
  EXPECT_FALSE(materialMasked(forced, {MaskRule::kNone, 0.2f, 0.0f, 0}));
}

// The thesis's scenes: floor, mirror and sphere masked in scene 1; the
// floor drawn by OpenGL in scene 2.
TEST(MaskRule, ThesisScenes) {
  const Scene one = loadSceneFile(test::sourcePath("scenes/room.json"));
  const Scene two = loadSceneFile(test::sourcePath("scenes/room-gl-floor.json"));
  std::vector<std::string> masked1, masked2;
  for (const Material& m : one.materials) {
    if (materialMasked(m, one.mask)) masked1.push_back(m.name);
  }
  for (const Material& m : two.materials) {
    if (materialMasked(m, two.mask)) masked2.push_back(m.name);
  }
  EXPECT_EQ(masked1, (std::vector<std::string>{"floor", "gold", "mirror"}));
  EXPECT_EQ(masked2, (std::vector<std::string>{"gold", "mirror"}));
}

}  // namespace
}  // namespace glint
