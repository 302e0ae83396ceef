#include "common/scene/scene_load.h"

#include <cmath>

#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/base/error.h"
#include "common/base/file_source.h"
#include "common/base/json_reader.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;

json minimalScene() {
  return json::parse(R"({
    "glint": 1,
    "image": {"width": 8, "height": 6},
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"m": {"color": [1, 0, 0]}},
    "lights": [{"type": "point", "position": [0, 5, 5]}],
    "objects": [
      {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"},
      {"type": "mesh", "positions": [0,0,0, 1,0,0, 0,1,0], "indices": [0, 1, 2], "material": "m"}
    ]
  })");
}

std::string loadError(const std::string& text, MemorySource files = {}, const LoadLimits& limits = {}) {
  try {
    loadScene(text, files, limits);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(loaded without error)";
}

TEST(SceneLoad, RoomMatchesTheThesis) {
  const Scene s = loadSceneFile(test::sourcePath("scenes/room.json"));
  EXPECT_EQ(s.frame.width, 640);
  EXPECT_EQ(s.frame.height, 480);
  EXPECT_EQ(s.geometry.triangles().size(), 10u);  // floor, 2 walls, ceiling, mirror
  EXPECT_EQ(s.geometry.spheres().size(), 1u);
  EXPECT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.frame.sampling.pattern, SamplePattern::kJittered);
  EXPECT_EQ(s.frame.sampling.samples, 4);
  EXPECT_EQ(s.frame.sampling.filter, FilterType::kTent);
}

TEST(SceneLoad, DefaultsAreTheFormats) {
  MemorySource files;
  const Scene s = loadScene(minimalScene().dump(), files);
  EXPECT_EQ(s.frame.sampling.pattern, SamplePattern::kRegular);
  EXPECT_EQ(s.frame.sampling.samples, 1);
  EXPECT_EQ(s.frame.sampling.filter, FilterType::kBox);
  EXPECT_EQ(s.frame.tracing.maxDepth, 5);
  EXPECT_FLOAT_EQ(s.frame.tracing.minWeight, 0.01f);
  EXPECT_EQ(s.mask.rule, MaskRule::kAuto);
  EXPECT_FLOAT_EQ(s.mask.minReflectivity, 0.2f);
  EXPECT_EQ(s.lights[0].attenuation, glm::vec3(1, 0, 0));
  const Material& m = s.materials[0];
  EXPECT_EQ(m.diffuse, 1.0f);
  EXPECT_EQ(m.shininess, 1.0f);
  EXPECT_EQ(m.ior, 1.0f);
  EXPECT_EQ(m.ambient, 0.0f);
  EXPECT_EQ(s.frame.camera.up, glm::vec3(0, 1, 0));
  // 8-bit values as a display shows them, unless the scene says linear.
  EXPECT_EQ(s.frame.output.encoding, Encoding::kSrgb);
  json linear = minimalScene();
  linear["image"]["encoding"] = "linear";
  EXPECT_EQ(loadScene(linear.dump(), files).frame.output.encoding, Encoding::kLinear);
}

// A mesh whose every triangle is dropped leaves nothing to see: a warning
// names it and why; a camera asked to fit such a scene says why there is
// nothing to frame. A mesh that keeps some triangles warns of nothing.
TEST(SceneLoad, AMeshWithNoTriangleLeftIsNamed) {
  json j = minimalScene();
  j["objects"][1]["positions"] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0, 0, 0, 1, 0, 0, 2, 0};  // collinear
  j["objects"][1]["indices"] = {0, 1, 2, 3, 4, 5};
  MemorySource files;
  const Scene s = loadScene(j.dump(), files);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], "objects[1]: all 2 of its triangles were dropped (a vertex not finite, or no area): "
                           "nothing of this mesh can be seen");
  EXPECT_TRUE(loadScene(minimalScene().dump(), files).warnings.empty());

  j["objects"].erase(0);
  j["camera"]["fit"] = true;
  const std::string error = loadError(j.dump(), files);
  EXPECT_NE(error.find("camera.fit: the scene has no object to frame (2 triangles were dropped: a vertex not "
                       "finite, or no area)"),
            std::string::npos)
      << error;
}

// emission times emission_texture, either alone the emission, none by
// default; a solid texture folds into the emission.
TEST(SceneLoad, EmissionAndItsTexture) {
  json j = minimalScene();
  j["textures"] = {{"glow", {{"type", "solid"}, {"color", {0.5, 1, 0.25}}}}};
  j["materials"]["both"] = {{"emission", {2, 2, 2}}, {"emission_texture", "glow"}};
  j["materials"]["texture"] = {{"emission_texture", "glow"}};
  j["materials"]["colour"] = {{"emission", {0.1, 0.2, 0.3}}};
  MemorySource files;
  const Scene s = loadScene(j.dump(), files);
  const auto material = [&s](const std::string& name) {
    for (const Material& m : s.materials) {
      if (m.name == name) return m;
    }
    ADD_FAILURE() << "no material " << name;
    return Material{};
  };
  EXPECT_EQ(material("m").emission, glm::vec3(0.0f));
  EXPECT_EQ(material("both").emission, glm::vec3(1.0f, 2.0f, 0.5f));
  EXPECT_EQ(material("texture").emission, glm::vec3(0.5f, 1.0f, 0.25f));
  EXPECT_EQ(material("colour").emission, glm::vec3(0.1f, 0.2f, 0.3f));
  for (const Material& m : s.materials) EXPECT_EQ(m.emissionTexture, -1) << m.name;
}

TEST(SceneLoad, TransformsScaleRotateTranslateInThatOrder) {
  json j = minimalScene();
  j["objects"][0]["transform"] = {{"scale", 2}, {"rotate", {0, 0, 1, 90}}, {"translate", {1, 0, 0}}};
  j["objects"][0]["center"] = {1, 0, 0};
  j["objects"][1]["transform"] = {{"scale", {2, 1, 1}}, {"rotate", {0, 0, 1, 90}}, {"translate", {0, 0, 3}}};
  MemorySource files;
  const Scene s = loadScene(j.dump(), files);
  // (1,0,0) -> scale 2 -> (2,0,0) -> rotate 90 about z -> (0,2,0) -> translate -> (1,2,0).
  EXPECT_NEAR(s.geometry.spheres()[0].centre.x, 1.0f, 1e-6f);
  EXPECT_NEAR(s.geometry.spheres()[0].centre.y, 2.0f, 1e-6f);
  EXPECT_FLOAT_EQ(s.geometry.spheres()[0].radius, 2.0f);
  // Mesh vertex (1,0,0) -> (2,0,0) -> (0,2,0) -> (0,2,3).
  const glm::vec3 v = s.geometry.positions()[1];
  EXPECT_NEAR(v.x, 0.0f, 1e-6f);
  EXPECT_NEAR(v.y, 2.0f, 1e-6f);
  EXPECT_NEAR(v.z, 3.0f, 1e-6f);
}

TEST(SceneLoad, ObjWithMtlAndTextureFromMemory) {
  MemorySource files;
  files.add("models/cube.obj",
            "mtllib cube.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "usemtl red\nf 1/1 2/2 3/3\nusemtl blue\nf 1/1 3/3 4/4\n");
  files.add("models/cube.mtl",
            "newmtl red\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 40\nd 0.5\nNi 1.3\n"
            "newmtl blue\nKd 0 0 1\nmap_Kd tex.bmp\n");
  // A 1x1 24-bit BMP: green.
  const unsigned char bmp[] = {'B', 'M', 58, 0, 0, 0, 0, 0, 0, 0, 54, 0, 0, 0, 40, 0, 0, 0, 1, 0, 0, 0, 1, 0,
                               0, 0, 1, 0, 24, 0, 0, 0, 0, 0, 4, 0, 0, 0, 0x13, 0x0b, 0, 0, 0x13, 0x0b, 0,
                               0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 255, 0, 0};
  files.add("models/tex.bmp", std::string(reinterpret_cast<const char*>(bmp), sizeof bmp));
  json j = minimalScene();
  j["objects"] = {{{"type", "mesh"}, {"file", "models/cube.obj"}}};
  const Scene s = loadScene(j.dump(), files);
  ASSERT_EQ(s.geometry.triangles().size(), 2u);
  ASSERT_EQ(s.materials.size(), 3u);  // m, red, blue
  const Material& red = s.materials[1];
  EXPECT_EQ(red.color, glm::vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(red.specular, 0.5f);
  EXPECT_FLOAT_EQ(red.shininess, 40.0f);
  EXPECT_FLOAT_EQ(red.transparency, 0.5f);
  EXPECT_FLOAT_EQ(red.ior, 1.3f);
  const Material& blue = s.materials[2];
  ASSERT_GE(blue.texture, 0);
  EXPECT_EQ(s.textures[static_cast<std::size_t>(blue.texture)].evaluate({0.5f, 0.5f}), glm::vec3(0, 1, 0));
}

struct BadCase {
  const char* name;
  std::function<void(json&)> edit;
  const char* message;
};

// Each bad scene is rejected with a message naming the JSON path.
TEST(SceneLoad, BadScenesNameThePlace) {
  const std::vector<BadCase> cases = {
      {"version", [](json& j) { j["glint"] = 2; }, "glint: this build of Glint reads scene format version 1 (\"glint\": 1)"},
      {"version 0", [](json& j) { j["glint"] = 0; }, "glint: this build of Glint reads scene format version 1 (\"glint\": 1)"},
      {"field of view over", [](json& j) { j["camera"]["fov_y"] = 180; }, "camera.fov_y: must be in (0, 179]"},
      {"field of view under", [](json& j) { j["camera"]["fov_y"] = 0; }, "camera.fov_y: must be in (0, 179]"},
      {"missing image", [](json& j) { j.erase("image"); }, "image: required key is missing"},
      {"unknown key", [](json& j) { j["camera"]["fov"] = 40; }, "camera.fov: unknown key"},
      {"unknown top key", [](json& j) { j["lighting"] = 1; }, "lighting: unknown key"},
      {"wrong type", [](json& j) { j["image"]["width"] = "640"; }, "image.width: must be a whole number"},
      {"fraction", [](json& j) { j["image"]["width"] = 6.5; }, "image.width: must be a whole number"},
      {"zero width", [](json& j) { j["image"]["width"] = 0; }, "image.width: must be in [1, 65536]"},
      {"negative radius", [](json& j) { j["objects"][0]["radius"] = -1; }, "objects[0].radius: must be > 0"},
      {"zero radius", [](json& j) { j["objects"][0]["radius"] = 0; }, "objects[0].radius: must be > 0"},
      {"unknown material", [](json& j) { j["objects"][0]["material"] = "gold"; },
       "objects[0].material: no material named 'gold'"},
      {"unknown texture", [](json& j) { j["materials"]["m"] = {{"texture", "wood"}}; },
       "materials.m.texture: no texture named 'wood'"},
      {"negative emission", [](json& j) { j["materials"]["m"]["emission"] = {1, -0.5, 0}; },
       "materials.m.emission: must not be negative"},
      {"negative colour", [](json& j) { j["materials"]["m"]["color"] = {0.5, 0.5, -0.1}; },
       "materials.m.color: must not be negative"},
      {"negative light", [](json& j) { j["lights"] = {{{"type", "point"}, {"position", {0, 5, 0}}, {"color", {-1, 1, 1}}}}; },
       "lights[0].color: must not be negative"},
      {"checker emission",
       [](json& j) {
         j["textures"] = {{"c", {{"type", "checker"}, {"colors", {{0, 0, 0}, {1, 1, 1}}}, {"scale", 2}}}};
         j["materials"]["m"]["emission_texture"] = "c";
       },
       "materials.m.emission_texture: must name an image or solid texture, not a checker"},
      {"unknown emission texture", [](json& j) { j["materials"]["m"]["emission_texture"] = "glow"; },
       "materials.m.emission_texture: no texture named 'glow'"},
      {"zero up", [](json& j) { j["camera"]["up"] = {0, 0, 0}; }, "camera.up: must not be the zero vector"},
      {"up along view", [](json& j) { j["camera"]["up"] = {0, 0, 1}; }, "camera.up: is parallel"},
      {"eye at target", [](json& j) { j["camera"]["look_at"] = {0, 0, 5}; }, "camera.look_at: must differ"},
      {"short vector", [](json& j) { j["camera"]["eye"] = {0, 0}; }, "camera.eye: must be an array of 3 numbers"},
      {"huge number", [](json& j) { j["camera"]["eye"][0] = 1e300; }, "camera.eye[0]: must be a finite number"},
      {"index out of range", [](json& j) { j["objects"][1]["indices"][2] = 3; },
       "objects[1].indices[2]: index out of range"},
      {"negative index", [](json& j) { j["objects"][1]["indices"][0] = -1; }, "objects[1].indices[0]: index out of range"},
      {"ragged positions", [](json& j) { j["objects"][1]["positions"].push_back(1); },
       "objects[1].positions: must hold x, y, z triples"},
      {"attenuation zero", [](json& j) { j["lights"][0]["attenuation"] = {0, 0, 0}; },
       "lights[0].attenuation: at least one of c, l, q must be positive"},
      {"attenuation negative", [](json& j) { j["lights"][0]["attenuation"] = {1, -1, 0}; },
       "lights[0].attenuation[1]: must be >= 0"},
      {"area light without area",
       [](json& j) {
         j["lights"][0] = {{"type", "area"}, {"position", {0, 3, 0}}, {"u", {1, 0, 0}}, {"v", {2, 0, 0}}};
       },
       "lights[0].v: must not be parallel to u"},
      {"area light too large for a float",
       [](json& j) {
         j["lights"][0] = {{"type", "area"}, {"position", {0, 3, 0}}, {"u", {1e38, 0, 0}}, {"v", {0, 0, 1e38}}};
       },
       "lights[0].v: with u spans an area of 1e+76, above what a float holds squared"},
      {"area light too small for a float",
       [](json& j) {
         j["lights"][0] = {{"type", "area"}, {"position", {0, 3, 0}}, {"u", {1e-30, 0, 0}}, {"v", {0, 0, 1e-30}}};
       },
       "lights[0].v: with u spans an area of 1e-60, below what a float holds squared"},
      {"area light samples", [](json& j) {
         j["lights"][0] = {{"type", "area"}, {"position", {0, 3, 0}}, {"u", {1, 0, 0}}, {"v", {0, 0, 1}},
                           {"samples", 0}};
       },
       "lights[0].samples"},
      {"point light with edges", [](json& j) { j["lights"][0]["u"] = {1, 0, 0}; }, "lights[0]"},
      {"sphere light without radius", [](json& j) { j["lights"][0] = {{"type", "sphere"}, {"position", {0, 3, 0}}}; },
       "lights[0].radius"},
      {"sphere light radius zero",
       [](json& j) { j["lights"][0] = {{"type", "sphere"}, {"position", {0, 3, 0}}, {"radius", 0}}; },
       "lights[0].radius: must be > 0"},
      {"sphere light samples", [](json& j) {
         j["lights"][0] = {{"type", "sphere"}, {"position", {0, 3, 0}}, {"radius", 1}, {"samples", 5000}};
       },
       "lights[0].samples"},
      {"sphere light with edges", [](json& j) {
         j["lights"][0] = {{"type", "sphere"}, {"position", {0, 3, 0}}, {"radius", 1}, {"u", {1, 0, 0}}};
       },
       "lights[0]"},
      {"negative aperture", [](json& j) { j["camera"]["aperture"] = -0.1; }, "camera.aperture"},
      {"zero focus", [](json& j) { j["camera"]["focus_distance"] = 0; }, "camera.focus_distance"},
      {"light samples", [](json& j) { j["sampling"]["light_samples"] = 5000; }, "sampling.light_samples"},
      {"light type", [](json& j) { j["lights"][0]["type"] = "sun"; },
       "lights[0].type: 'sun' is not one of: point, area, spot, directional, sphere"},
      {"spot cones", [](json& j) {
         j["lights"][0] = {{"type", "spot"}, {"position", {0, 3, 0}}, {"direction", {0, -1, 0}},
                           {"inner_angle", 40}, {"outer_angle", 30}};
       },
       "lights[0].inner_angle: must not exceed outer_angle"},
      {"spot outer angle", [](json& j) {
         j["lights"][0] = {{"type", "spot"}, {"position", {0, 3, 0}}, {"direction", {0, -1, 0}}, {"outer_angle", 95}};
       },
       "lights[0].outer_angle"},
      {"directional without direction", [](json& j) { j["lights"][0] = {{"type", "directional"}, {"direction", {0, 0, 0}}}; },
       "lights[0].direction: must be a direction, not zero"},
      {"directional with a position", [](json& j) {
         j["lights"][0] = {{"type", "directional"}, {"direction", {0, -1, 0}}, {"position", {0, 3, 0}}};
       },
       "lights[0]"},
      {"directional attenuation", [](json& j) {
         j["lights"][0] = {{"type", "directional"}, {"direction", {0, -1, 0}}, {"attenuation", {1, 0, 1}}};
       },
       "lights[0]"},
      {"object type", [](json& j) { j["objects"][0]["type"] = "cube"; }, "objects[0].type: 'cube' is not one of"},
      {"regular 3", [](json& j) { j["sampling"] = {{"samples", 3}}; }, "sampling.samples: the regular pattern"},
      {"filter", [](json& j) { j["sampling"] = {{"filter", "lanczos"}}; }, "sampling.filter: 'lanczos'"},
      {"max depth", [](json& j) { j["tracing"] = {{"max_depth", 0}}; }, "tracing.max_depth: must be in [1, 64]"},
      {"transparency", [](json& j) { j["materials"]["m"]["transparency"] = 1.5; },
       "materials.m.transparency: must be in [0, 1]"},
      {"ior", [](json& j) { j["materials"]["m"]["ior"] = 0; }, "materials.m.ior: must be > 0"},
      {"raytrace", [](json& j) { j["materials"]["m"]["raytrace"] = "yes"; },
       "materials.m.raytrace: must be true, false or \"auto\""},
      {"zero scale", [](json& j) { j["objects"][1]["transform"] = {{"scale", 0}}; },
       "objects[1].transform.scale: must not be zero"},
      {"zero axis", [](json& j) { j["objects"][1]["transform"] = {{"rotate", {0, 0, 0, 30}}}; },
       "objects[1].transform.rotate: the rotation axis must not be the zero vector"},
      {"ellipsoid", [](json& j) { j["objects"][0]["transform"] = {{"scale", {1, 2, 1}}}; },
       "objects[0].transform.scale: a sphere takes only a uniform scale"},
      {"quad not planar",
       [](json& j) {
         j["objects"][1] = {{"type", "quad"}, {"corners", {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 1}}}, {"material", "m"}};
       },
       "objects[1].corners: the four corners are not coplanar"},
      {"mesh both", [](json& j) { j["objects"][1]["file"] = "a.obj"; }, "objects[1]: a mesh needs either file or positions"},
      {"missing file", [](json& j) { j["objects"][1] = {{"type", "mesh"}, {"file", "nowhere.obj"}}; },
       "objects[1].file: file 'nowhere.obj' was not sent"},
      {"missing texture file",
       [](json& j) { j["textures"] = {{"t", {{"type", "image"}, {"file", "t.png"}}}}; },
       "textures.t.file: file 't.png' was not sent"},
      {"objects not array", [](json& j) { j["objects"] = {{"a", 1}}; }, "objects: must be an array"},
      {"top level", [](json& j) { j = json::array(); }, "(top level): must be an object"},
  };
  for (const BadCase& c : cases) {
    json j = minimalScene();
    c.edit(j);
    EXPECT_NE(loadError(j.dump()).find(c.message), std::string::npos)
        << c.name << ": got '" << loadError(j.dump()) << "'";
  }
}

TEST(SceneLoad, MalformedAndTruncatedJson) {
  const std::string good = minimalScene().dump();
  EXPECT_NE(loadError(good.substr(0, good.size() / 2)).find("not valid JSON"), std::string::npos);
  EXPECT_NE(loadError("{\"glint\": 1,,}").find("line 1, column"), std::string::npos);
  EXPECT_NE(loadError("").find("not valid JSON"), std::string::npos);
  EXPECT_NE(loadError("\xff\xfe").find("not valid JSON"), std::string::npos);
}

TEST(SceneLoad, LimitsRejectHugeMeshesAndImagesBeforeAllocating) {
  LoadLimits limits;
  limits.maxTriangles = 1;
  json j = minimalScene();
  j["objects"][1]["positions"] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  j["objects"][1]["indices"] = {0, 1, 2, 1, 3, 2};
  EXPECT_NE(loadError(j.dump(), {}, limits).find("more triangles than the limit of 1"), std::string::npos);

  LoadLimits pixels;
  pixels.maxImagePixels = 10;
  EXPECT_NE(loadError(minimalScene().dump(), {}, pixels).find("image: image of 8x6 pixels is over the limit"),
            std::string::npos);

  // A BMP header announcing 100000 x 100000 pixels.
  MemorySource files;
  unsigned char bmp[54] = {'B', 'M', 0, 0, 0, 0, 0, 0, 0, 0, 54, 0, 0, 0, 40, 0, 0, 0, 0xa0, 0x86, 0x01, 0,
                           0xa0, 0x86, 0x01, 0, 1, 0, 24, 0};
  files.add("big.bmp", std::string(reinterpret_cast<const char*>(bmp), sizeof bmp));
  json t = minimalScene();
  t["textures"] = {{"t", {{"type", "image"}, {"file", "big.bmp"}}}};
  EXPECT_NE(loadError(t.dump(), files).find("textures.t.file: image of 100000x100000 pixels is over the limit"),
            std::string::npos)
      << loadError(t.dump(), files);

  files.add("junk.png", "not an image at all");
  t["textures"]["t"]["file"] = "junk.png";
  EXPECT_NE(
      loadError(t.dump(), files).find("textures.t.file: not a PNG, BMP, JPEG, TGA, Radiance HDR or OpenEXR image"),
      std::string::npos);
  // Other formats stb_image knows never reach it; a PNG that is not one is unreadable.
  files.add("anim.gif", std::string("GIF89a\x01\x00\x01\x00\x00\x00\x00;", 14));
  t["textures"]["t"]["file"] = "anim.gif";
  EXPECT_NE(
      loadError(t.dump(), files).find("textures.t.file: not a PNG, BMP, JPEG, TGA, Radiance HDR or OpenEXR image"),
      std::string::npos);
  files.add("broken.png", std::string("\x89PNG\r\n\x1a\n", 8) + "garbage");
  t["textures"]["t"]["file"] = "broken.png";
  EXPECT_NE(
      loadError(t.dump(), files).find("textures.t.file: not a readable PNG, BMP, JPEG, TGA, Radiance HDR or OpenEXR"),
      std::string::npos)
      << loadError(t.dump(), files);
}

// What a scene will hold is counted from each image's header before decoding
// (four names of one 8192x8192 PNG once took glintd to 4.3 GB): a header
// alone over the budget fails on the budget, not on the missing pixels.
TEST(SceneLoad, SceneBudgetCountsImagesBeforeDecoding) {
  LoadLimits limits;
  limits.maxSceneBytes = std::size_t{32} << 20;
  MemorySource files;
  files.add("huge.bmp", test::bmp(4096, 4096, false));  // 48 MiB of texels announced
  json j = minimalScene();
  j["textures"] = {{"t", {{"type", "image"}, {"file", "huge.bmp"}}}};
  EXPECT_NE(loadError(j.dump(), files, limits)
                .find("textures.t.file: the scene would hold 48.0 MiB once built, 16.0 MiB over the limit for one "
                      "scene of 32.0 MiB"),
            std::string::npos)
      << loadError(j.dump(), files, limits);
}

TEST(SceneLoad, SceneBudgetCountsEveryTextureMeshAndSphere) {
  MemorySource files;
  json j = minimalScene();
  for (const std::string name : {"a", "b", "c", "d"}) {
    files.add(name + ".bmp", test::bmp(1024, 1024, true));  // 3 MiB of texels each
    j["textures"][name] = {{"type", "image"}, {"file", name + ".bmp"}};
  }
  // Each decode holds stb_image's 3 MiB of pixels and 3 MiB of RGB beside
  // the texels kept: three fit, the fourth does not while it decodes.
  LoadLimits limits;
  limits.maxSceneBytes = std::size_t{16} << 20;
  EXPECT_NE(loadError(j.dump(), files, limits)
                .find("textures.d.file: the scene would hold 18.0 MiB while it decodes, 2.0 MiB over"),
            std::string::npos)
      << loadError(j.dump(), files, limits);
  // One file named by all four textures is decoded, and counted, once.
  for (const char* name : {"a", "b", "c", "d"}) j["textures"][name]["file"] = "a.bmp";
  SceneBudget shared(limits);
  const Scene one = loadScene(j.dump(), files, shared);
  EXPECT_EQ(one.textures[0].image, one.textures[3].image);
  EXPECT_LT(shared.used(), std::size_t{4} << 20);

  // Without textures the scene holds a sphere and a triangle, each with its BVH share.
  SceneBudget budget;
  loadScene(minimalScene().dump(), files, budget);
  EXPECT_EQ(budget.used(), SceneBudget::kBytesPerSphere + 3 * SceneBudget::kBytesPerVertex +
                               SceneBudget::kBytesPerTriangle + 2 * SceneBudget::kBvhBytesPerPrimitive);
}

// Many materials of an asset share one atlas: an OBJ's 64 materials naming
// one map_Kd, the OBJ named by two objects and the atlas by a scene texture
// as well, decode and count the image once (3 MiB of texels under a 10 MiB
// limit; it was decoded for every material, 192 MiB).
TEST(SceneLoad, AnImageSharedByMaterialsOfMeshFilesIsDecodedOnce) {
  MemorySource files;
  std::string mtl, obj = "mtllib atlas.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n";
  for (int i = 0; i < 64; ++i) {
    mtl += "newmtl m" + std::to_string(i) + "\nKd 1 1 1\nmap_Kd atlas.bmp\n";
    obj += "usemtl m" + std::to_string(i) + "\nf 1/1 2/1 3/1\n";
  }
  files.add("models/atlas.mtl", mtl);
  files.add("models/atlas.obj", obj);
  files.add("models/atlas.bmp", test::bmp(1024, 1024, true));
  json j = minimalScene();
  j["textures"] = {{"t", {{"type", "image"}, {"file", "models/atlas.bmp"}}}};
  j["objects"] = {{{"type", "mesh"}, {"file", "models/atlas.obj"}}, {{"type", "mesh"}, {"file", "models/atlas.obj"}}};
  LoadLimits limits;
  limits.maxSceneBytes = std::size_t{10} << 20;
  SceneBudget budget(limits);
  const Scene scene = loadScene(j.dump(), files, budget);
  ASSERT_EQ(scene.textures.size(), 129u);  // the scene's, and 64 for each use of the OBJ
  for (const Texture& t : scene.textures) EXPECT_EQ(t.image, scene.textures[0].image);
  EXPECT_LT(budget.used(), std::size_t{4} << 20);
}

// A budget drawn from a shared gauge gives its bytes back when it goes, and a
// load that does not fit beside the others fails naming the gauge.
TEST(SceneLoad, SharedGaugeIsDrawnAndGivenBack) {
  MemoryGauge gauge(1000, "the test gauge");
  {
    SceneBudget budget({}, "the limit for one scene", &gauge);
    budget.charge(600, "a");
    EXPECT_EQ(gauge.used(), 600u);
    SceneBudget other({}, "the limit for one scene", &gauge);
    try {
      other.charge(500, "b");
      FAIL() << "500 bytes fitted beside 600 in a gauge of 1000";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("b: the scene's"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("the test gauge"), std::string::npos) << e.what();
    }
    other.charge(400, "c");
    EXPECT_EQ(gauge.used(), 1000u);
  }
  EXPECT_EQ(gauge.used(), 0u);
}

// A key written twice in one object is an error naming the object and the
// key: a second "objects": [] rendered an empty scene with exit 0 when the
// last one won. The same key in different objects, or inside strings and
// comments, is fine.
TEST(SceneLoad, AKeyWrittenTwiceIsAnError) {
  std::string text = minimalScene().dump();
  text.insert(text.rfind('}'), ",\"objects\": []");
  EXPECT_NE(loadError(text).find("(top level): the key 'objects' is written twice"), std::string::npos)
      << loadError(text);
  text = minimalScene().dump();
  const std::string radius = "\"radius\":1";
  text.replace(text.find(radius), radius.size(), "\"radius\":1, /* \"radius\": 3 */ \"radius\":2");
  EXPECT_NE(loadError(text).find("objects[0]: the key 'radius' is written twice"), std::string::npos)
      << loadError(text);
  json j = minimalScene();
  j["materials"]["second"] = {{"color", {1, 0, 0}}};  // "color" in two materials
  text = j.dump();
  text.insert(1, "// \"glint\": 1,\n");
  EXPECT_EQ(loadError(text), "(loaded without error)");
}

// "fit": true moves the camera along its direction onto the objects' box
// (common/scene/camera.h's fitCamera, tested there): here the scene's
// objects are a sphere of radius 1 at the origin and a triangle reaching
// (1, 1, 0), so the box is [-1, 1]^3 and its centre the origin.
TEST(SceneLoad, FitFramesTheObjects) {
  json j = minimalScene();
  j["camera"] = {{"eye", {20, 0, 0}}, {"look_at", {30, 0, 0}}, {"fit", true}};
  MemorySource files;
  const Scene s = loadScene(j.dump(), files);
  const CameraSpec& c = s.frame.camera;
  EXPECT_NEAR(glm::length(c.lookAt), 0.0f, 1e-6f);
  EXPECT_NEAR(c.eye.y, 0.0f, 1e-6f);
  EXPECT_NEAR(c.eye.z, 0.0f, 1e-6f);
  // The box's sphere (radius sqrt 3) in the narrower, vertical field of 45 degrees.
  EXPECT_NEAR(c.eye.x, -std::sqrt(3.0f) / std::sin(glm::radians(22.5f)), 1e-4f);
  j["camera"]["fit"] = false;
  EXPECT_EQ(loadScene(j.dump(), files).frame.camera.eye, glm::vec3(20, 0, 0));
  j["camera"]["fit"] = true;
  j["objects"] = json::array();
  EXPECT_NE(loadError(j.dump()).find("camera.fit: the scene has no object to frame"), std::string::npos)
      << loadError(j.dump());
}

// A number beyond a double is an error at its path, like every other scene
// error (it used to reach the user as "internal error: [json.exception...").
TEST(SceneLoad, NumberOutOfRangeNamesItsPath) {
  std::string text = minimalScene().dump();
  const std::string radius = "\"radius\":1";
  text.replace(text.find(radius), radius.size(), "\"radius\":1e999");
  EXPECT_NE(loadError(text).find("objects[0].radius: number overflow parsing '1e999' (out of range)"),
            std::string::npos)
      << loadError(text);
  json j = minimalScene();
  text = j.dump();
  const std::string positions = "[0,0,0,1,0,0,0,1,0]";
  text.replace(text.find(positions), positions.size(), "[0,0,0,1,0,0,0,-1e400,0]");
  EXPECT_NE(loadError(text).find("objects[1].positions[7]: number overflow"), std::string::npos) << loadError(text);
}

TEST(SceneLoad, BadObjFiles) {
  MemorySource files;
  files.add("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
  json j = minimalScene();
  j["objects"][1] = {{"type", "mesh"}, {"file", "bad.obj"}, {"material", "m"}};
  EXPECT_NE(loadError(j.dump(), files).find("objects[1].file:"), std::string::npos) << loadError(j.dump(), files);
}

TEST(SceneLoad, MissingSceneFileNamesThePath) {
  try {
    loadSceneFile("/nonexistent/scene.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.json"), std::string::npos);
  }
}

// The text's shape, counted over its bytes: brackets, separators and colons
// inside strings (escaped quotes too) and comments do not count.
TEST(SceneLoad, MeasureJsonSkipsStringsAndComments) {
  const JsonShape shape = measureJson(R"({"a": [1, 2, {"b": "x,[:\"]{"}], // [ , :
                                          /* { , } */ "c": 3})");
  EXPECT_EQ(shape.depth, 3);
  EXPECT_EQ(shape.members, 3u);
  EXPECT_EQ(shape.values, 1u + 3 + 3);  // one, three containers, three separators
}

// A scene nested deeper than the limit is refused before it is parsed: a
// million brackets (a parser's recursion, and 70 bytes a level) are named in
// the message, not followed.
TEST(SceneLoad, DeepNestingIsRefusedBeforeTheParse) {
  const std::string deep = std::string(1'000'000, '[') + std::string(1'000'000, ']');
  EXPECT_NE(loadError(deep).find("nests arrays and objects 1000000 deep; at most 64"), std::string::npos)
      << loadError(deep);
  json scene = minimalScene();
  json nest = json::array();
  for (int i = 0; i < 70; ++i) nest = json::array({nest});
  scene["extra"] = nest;
  EXPECT_NE(loadError(scene.dump()).find("deep; at most 64"), std::string::npos);
}

// A long array costs its parse about 32 bytes a value, charged to the
// scene's budget before the parse, where the JSON may take a quarter of it:
// three million values (92 MiB) do not fit a quarter of 64 MiB, and the
// message names the JSON and the limit; the same scene is parsed under a
// budget whose quarter they fit.
TEST(SceneLoad, LongArraysAreChargedBeforeTheParse) {
  json scene = minimalScene();
  std::string text = scene.dump();
  std::string ones = ", \"padding\": [";
  for (int i = 0; i < 3'000'000; ++i) ones += "1,";
  ones += "1]}";
  text.replace(text.size() - 1, 1, ones);
  LoadLimits limits;
  limits.maxSceneBytes = std::size_t{64} << 20;
  const std::string error = loadError(text, {}, limits);
  EXPECT_NE(error.find("the scene's JSON (30000"), std::string::npos) << error;
  EXPECT_NE(error.find("parsing it would take 91.6 MiB, over the 16.0 MiB (a quarter of the limit for one scene)"),
            std::string::npos)
      << error;
  limits.maxSceneBytes = std::size_t{512} << 20;
  EXPECT_NE(loadError(text, {}, limits).find("padding"), std::string::npos);  // parsed: the unknown key is named
}

}  // namespace
}  // namespace glint
