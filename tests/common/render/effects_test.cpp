#include "common/render/effects.h"

#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/scene/scene_load.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;

// Renders with the derived plan and with every effect on: the images must be
// byte-identical (turning off an absent effect changes nothing).
std::pair<FrameResult, FrameResult> derivedAndFull(const Scene& s) {
  FrameResult derived = test::render(s, EffectPlan::derive(s), 2);
  FrameResult full = test::render(s, test::everyEffect(s), 2);
  EXPECT_EQ(derived.image.rgb, full.image.rgb);
  return {std::move(derived), std::move(full)};
}

json sphereScene() {
  return json::parse(R"({
    "glint": 1, "image": {"width": 48, "height": 32},
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"m": {"color": [1, 0.5, 0.2], "ambient": 0.1, "specular": 0.4, "shininess": 20}},
    "lights": [{"type": "point", "position": [2, 3, 4]}],
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]
  })");
}

TEST(Effects, RoomPlan) {
  const Scene s = loadSceneFile(test::sourcePath("scenes/room.json"));
  const EffectPlan p = EffectPlan::derive(s);
  EXPECT_TRUE(p.shadows);
  EXPECT_TRUE(p.reflection);
  EXPECT_FALSE(p.refraction);
  EXPECT_TRUE(p.textures);
  EXPECT_TRUE(p.attenuation);
  EXPECT_TRUE(p.antialiasing);
  EXPECT_FALSE(p.emission);
}

TEST(Effects, NoShadowRaysWhereNothingCanCastAShadow) {
  const Scene s = test::sceneFromJson(sphereScene().dump());
  EXPECT_FALSE(EffectPlan::derive(s).shadows);
  EXPECT_FALSE(EffectPlan::derive(s).attenuation);
  EXPECT_FALSE(EffectPlan::derive(s).reflection);
  EXPECT_FALSE(EffectPlan::derive(s).textures);
  EXPECT_FALSE(EffectPlan::derive(s).antialiasing);
  const auto [derived, full] = derivedAndFull(s);
  EXPECT_EQ(derived.stats.shadow, 0u);
  EXPECT_GT(full.stats.shadow, 0u);
}

TEST(Effects, BlackLightsAndUnlitMaterialsCastNoShadowRays) {
  json j = sphereScene();
  j["lights"].push_back({{"type", "point"}, {"position", {-2, 3, 4}}, {"color", {0, 0, 0}}});
  j["objects"].push_back({{"type", "sphere"}, {"center", {1.5, 0, 0}}, {"radius", 0.4}, {"material", "m"}});
  const Scene s = test::sceneFromJson(j.dump());
  const EffectPlan plan = EffectPlan::derive(s);
  EXPECT_TRUE(plan.shadows);
  EXPECT_FALSE(plan.lights[1]);
  const auto [derived, full] = derivedAndFull(s);
  EXPECT_LT(derived.stats.shadow, full.stats.shadow);  // the black light casts none

  json mirror = j;
  mirror["materials"]["m"] = {{"ambient", 0.2}, {"diffuse", 0}, {"reflectivity", 0.5}};
  const Scene m = test::sceneFromJson(mirror.dump());
  EXPECT_FALSE(EffectPlan::derive(m).materials[0].direct);
  const auto [d2, f2] = derivedAndFull(m);
  EXPECT_EQ(d2.stats.shadow, 0u);
  EXPECT_GT(f2.stats.shadow, 0u);
}

TEST(Effects, SoftShadowsOnlyWhereASoftLightCanBeBlocked) {
  // An area light facing down at the sphere, and a sphere light above it.
  for (const json& light :
       {json{{"type", "area"}, {"position", {0, 4, 0}}, {"u", {1, 0, 0}}, {"v", {0, 0, 1}}, {"samples", 4}},
        json{{"type", "sphere"}, {"position", {0, 4, 0}}, {"radius", 0.5}, {"samples", 4}}}) {
    json j = sphereScene();
    j["lights"][0] = light;
    const Scene alone = test::sceneFromJson(j.dump());
    EXPECT_FALSE(EffectPlan::derive(alone).softShadows) << light;  // one sphere cannot shadow itself
    EXPECT_EQ(derivedAndFull(alone).first.stats.shadow, 0u) << light;
    j["objects"].push_back({{"type", "sphere"}, {"center", {0, -2, 0}}, {"radius", 0.5}, {"material", "m"}});
    const Scene two = test::sceneFromJson(j.dump());
    EXPECT_TRUE(EffectPlan::derive(two).softShadows) << light;
    EXPECT_GT(derivedAndFull(two).first.stats.shadow, 0u) << light;
  }
  // Every scene of the project without a soft light has no soft shadows.
  for (const char* name : {"scenes/room.json", "scenes/glass.json", "scenes/bunny.json", "scenes/lights.json"}) {
    EXPECT_FALSE(EffectPlan::derive(loadSceneFile(test::sourcePath(name))).softShadows) << name;
  }
  for (const char* name : {"scenes/soft-shadows.json", "scenes/sphere-light.json"}) {
    EXPECT_TRUE(EffectPlan::derive(loadSceneFile(test::sourcePath(name))).softShadows) << name;
  }
}

// Only the scene with an environment image looks one up.
TEST(Effects, EnvironmentOnlyWhereTheSceneHasOne) {
  for (const char* name : {"scenes/room.json", "scenes/glass.json", "scenes/bunny.json", "scenes/glossy.json",
                           "scenes/lights.json", "scenes/soft-shadows.json", "scenes/sphere-light.json"}) {
    EXPECT_FALSE(EffectPlan::derive(loadSceneFile(test::sourcePath(name))).environment) << name;
  }
  const Scene sky = loadSceneFile(test::sourcePath("scenes/environment.json"));
  EXPECT_TRUE(EffectPlan::derive(sky).environment);
  // A camera that sees only the sky and no light or material: that is all it simulates.
  Scene bare = sky;
  bare.frame.sampling = {};
  bare.materials.clear();
  bare.lights.clear();
  bare.geometry = Geometry{};
  const EffectPlan plan = EffectPlan::derive(bare);
  for (const NamedEffect& e : namedEffects(plan)) EXPECT_EQ(e.needed, std::string(e.name) == "environment") << e.name;
}

// The raster pass draws shadow maps only where a shadow can fall on a
// surface OpenGL draws: something casts one, a lit material is left to
// OpenGL by the mask, and the maps are not turned off.
TEST(Effects, ShadowMapsOnlyWhereARasterSurfaceCanBeShadowed) {
  const Scene room = loadSceneFile(test::sourcePath("scenes/room.json"));
  const EffectPlan plan = EffectPlan::derive(room);
  MaskSettings mask = room.mask;
  EXPECT_TRUE(rasterShadows(room, plan, mask));
  mask.shadowMap = 0;
  EXPECT_FALSE(rasterShadows(room, plan, mask));
  mask = room.mask;
  mask.rule = MaskRule::kAll;  // nothing is drawn by OpenGL
  EXPECT_FALSE(rasterShadows(room, plan, mask));
  mask.rule = MaskRule::kAuto;
  mask.minReflectivity = -1.0f;  // every material traced (reflectivity >= 0 > -1)
  EXPECT_FALSE(rasterShadows(room, plan, mask));
  mask.rule = MaskRule::kNone;
  EXPECT_TRUE(rasterShadows(room, plan, mask));

  const Scene lone = test::sceneFromJson(sphereScene().dump());  // a sphere alone shadows nothing
  EXPECT_FALSE(rasterShadows(lone, EffectPlan::derive(lone), lone.mask));
}

TEST(Effects, NoSecondaryRaysAtDepthOneOrBelowMinWeight) {
  Scene s = loadSceneFile(test::sourcePath("scenes/room.json"));
  s.frame.width = 64;
  s.frame.height = 48;
  s.frame.tracing.maxDepth = 1;
  EXPECT_FALSE(EffectPlan::derive(s).reflection);
  const auto [derived, full] = derivedAndFull(s);
  EXPECT_EQ(derived.stats.reflection, 0u);

  s.frame.tracing.maxDepth = 5;
  s.frame.tracing.minWeight = 0.9f;  // above every reflectivity in the room
  EXPECT_FALSE(EffectPlan::derive(s).reflection);
  const auto [d2, f2] = derivedAndFull(s);
  EXPECT_EQ(d2.stats.reflection, 0u);
}

TEST(Effects, NoRefractionWithoutTransparency) {
  Scene s = loadSceneFile(test::sourcePath("scenes/room.json"));
  s.frame.width = 64;
  s.frame.height = 48;
  EXPECT_FALSE(EffectPlan::derive(s).refraction);
  const auto [derived, full] = derivedAndFull(s);
  EXPECT_EQ(derived.stats.refraction, 0u);
  EXPECT_GT(derived.stats.reflection, 0u);
}

// Emission is added only where a material emits; with it, the derived plan
// still renders the bytes every effect does, and an emitting sphere without
// lights shows its emission (ambient 0.1 x colour plus it) and nothing else.
TEST(Effects, EmissionOnlyWhereAMaterialEmits) {
  json j = sphereScene();
  j["materials"]["glow"] = {{"color", {1, 1, 1}}, {"ambient", 0.1}, {"emission", {0.5, 0.25, 0.0}}};
  j["objects"].push_back({{"type", "sphere"}, {"center", {1.5, 0, 0}}, {"radius", 0.4}, {"material", "glow"}});
  const Scene s = test::sceneFromJson(j.dump());
  const EffectPlan plan = EffectPlan::derive(s);
  EXPECT_TRUE(plan.emission);
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    EXPECT_EQ(plan.materials[i].emits, s.materials[i].name == "glow") << s.materials[i].name;
    EXPECT_FALSE(plan.materials[i].textured) << s.materials[i].name;
  }
  derivedAndFull(s);
  EXPECT_FALSE(EffectPlan::derive(test::sceneFromJson(sphereScene().dump())).emission);

  j["lights"] = json::array();
  j["objects"].erase(0);
  j["image"]["encoding"] = "linear";  // bytes are the light itself
  const Scene dark = test::sceneFromJson(j.dump());
  const FrameResult r = test::render(dark, EffectPlan::derive(dark), 1);
  const test::Rgb centre = test::pixelAt(r.image, 35, 16);  // the sphere: 1.5 right of the middle, 11.6 pixels
  EXPECT_EQ(centre.r, std::lround(255 * 0.6f));
  EXPECT_EQ(centre.g, std::lround(255 * 0.35f));
  EXPECT_EQ(centre.b, std::lround(255 * 0.1f));
}

TEST(Effects, GlassSceneRefracts) {
  Scene s = loadSceneFile(test::sourcePath("scenes/glass.json"));
  s.frame.width = 64;
  s.frame.height = 48;
  EXPECT_TRUE(EffectPlan::derive(s).refraction);
  const auto [derived, full] = derivedAndFull(s);
  EXPECT_GT(derived.stats.refraction, 0u);
  EXPECT_EQ(derived.stats.nonFiniteSamples, 0u);
}

}  // namespace
}  // namespace glint
