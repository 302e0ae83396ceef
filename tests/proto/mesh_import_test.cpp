// glTF and PLY meshes: Debian's sample models (assimp-testmodels) import
// with their triangles, textures and node transforms; a server gets the
// imported mesh as a blob that loads into the same scene, never the files an
// importer would parse; a damaged or hostile blob is refused, never trusted.
#include <filesystem>
#include <functional>
#include <fstream>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/base/error.h"
#include "common/base/file_source.h"
#include "common/scene/mesh_blob.h"
#include "common/scene/mesh_import.h"
#include "common/scene/scene_load.h"
#include "proto/scene_bundle.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
const fs::path kModels = "/usr/share/assimp/models";  // Debian's assimp-testmodels (make deps)

MeshModel import(const fs::path& file, bool withMaterials = true) {
  DirectorySource files(file.parent_path(), std::size_t{1} << 28);
  SceneBudget budget;
  return importMeshFile(files, file.filename().string(), "test", budget, withMaterials);
}

std::size_t triangles(const MeshModel& m) {
  std::size_t n = 0;
  for (const MeshInput& mesh : m.meshes) n += mesh.indices.size() / 3;
  return n;
}

// The corners of every triangle, in order: what the scene's geometry is made of.
std::vector<glm::vec3> corners(const MeshModel& m) {
  std::vector<glm::vec3> out;
  for (const MeshInput& mesh : m.meshes) {
    for (const std::uint32_t i : mesh.indices) out.push_back(mesh.positions[i]);
  }
  return out;
}

TEST(MeshImport, DebianSampleModels) {
  ASSERT_TRUE(fs::exists(kModels)) << "install assimp-testmodels (make deps)";
  const MeshModel gltf = import(kModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf");
  EXPECT_EQ(triangles(gltf), 12u);
  ASSERT_EQ(gltf.textures.size(), 1u);  // CesiumLogoFlat.png, beside the .gltf
  EXPECT_GT(gltf.textures[0].image->width, 0);
  ASSERT_EQ(gltf.meshes.size(), 1u);
  EXPECT_EQ(gltf.materials[gltf.meshes[0].material].texture, 0);
  EXPECT_EQ(gltf.meshes[0].uvs.size(), gltf.meshes[0].positions.size());
  // Its sampler: wrapS MIRRORED_REPEAT (its u runs to 6: the logo reads
  // forwards on every face), wrapT CLAMP_TO_EDGE, magFilter LINEAR.
  EXPECT_EQ(gltf.textures[0].wrap[0], TextureWrap::kMirroredRepeat);
  EXPECT_EQ(gltf.textures[0].wrap[1], TextureWrap::kClampToEdge);
  EXPECT_EQ(gltf.textures[0].filter, ImageFilter::kBilinear);
  const MeshModel glb = import(kModels / "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb");
  EXPECT_EQ(corners(glb), corners(gltf));  // one model, text or binary, texture embedded
  EXPECT_EQ(glb.textures.size(), 1u);
  // The binary sample's sampler repeats both ways (its JSON says so).
  EXPECT_EQ(glb.textures[0].wrap[0], TextureWrap::kRepeat);
  EXPECT_EQ(glb.textures[0].wrap[1], TextureWrap::kRepeat);
  EXPECT_EQ(glb.textures[0].filter, ImageFilter::kBilinear);

  const MeshModel ply = import(kModels / "PLY/cube.ply"), binary = import(kModels / "PLY/cube_binary.ply");
  EXPECT_EQ(triangles(ply), 12u);
  EXPECT_EQ(corners(binary), corners(ply));
  EXPECT_GT(triangles(import(kModels / "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb")), 100000u);
  try {
    import(kModels / "PLY/points.ply");
    ADD_FAILURE() << "points.ply imported";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("test: 'points.ply' cannot be imported: Validation failed: Mesh  contains "
                                         "no faces"),
              std::string::npos)
        << e.what();
  }
}

// A glTF written here: one triangle under a node that scales by 2 and moves
// by (1, 2, 3).
TEST(MeshImport, NodeTransformsAreApplied) {
  const fs::path dir = fs::temp_directory_path() / "glint_mesh_import";
  fs::create_directories(dir);
  std::ofstream(dir / "tri.gltf") << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0, "translation": [1, 2, 3], "scale": [2, 2, 2]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
  const MeshModel m = import(dir / "tri.gltf");
  EXPECT_EQ(corners(m), (std::vector<glm::vec3>{{1, 2, 3}, {3, 2, 3}, {1, 4, 3}}));
  fs::remove_all(dir);
}

// A scene may take its camera from a glTF file: the first perspective
// camera, placed by its node and the node's parent; through a bundle too.
TEST(MeshImport, CameraFromAGltfFile) {
  const fs::path dir = fs::temp_directory_path() / "glint_gltf_camera";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // Camera node 2: translation (1, 1, 10), turned 90 degrees about +y (so it
  // looks down -x), child of node 1, which moves by (0, 1, 0).
  std::ofstream(dir / "cam.gltf") << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"mesh": 0}, {"translation": [0, 1, 0], "children": [2]},
              {"camera": 1, "translation": [1, 1, 10], "rotation": [0, 0.70710678, 0, 0.70710678]}],
    "cameras": [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 9}},
                {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
  std::ofstream(dir / "scene.json") << R"({"glint": 1, "image": {"width": 8, "height": 6},
    "camera": {"file": "cam.gltf"}, "lights": [{"type": "point", "position": [0, 5, 5]}],
    "objects": [{"type": "mesh", "file": "cam.gltf"}]})";
  const proto::LoadedBundle loaded = proto::loadSceneBundle(dir / "scene.json");
  const CameraSpec& c = loaded.scene.frame.camera;
  EXPECT_LT(glm::length(c.eye - glm::vec3(1, 2, 10)), 1e-5f);
  EXPECT_LT(glm::length(c.lookAt - glm::vec3(0, 2, 10)), 1e-5f);
  EXPECT_LT(glm::length(c.up - glm::vec3(0, 1, 0)), 1e-5f);
  EXPECT_NEAR(c.fovY, 45.8366f, 1e-3f);
  SceneBudget budget;
  const Scene there = proto::loadBundle(loaded.bundle, budget);
  EXPECT_EQ(there.frame.camera.eye, c.eye);
  EXPECT_EQ(there.frame.camera.lookAt, c.lookAt);
  EXPECT_EQ(there.frame.camera.fovY, c.fovY);

  std::ofstream(dir / "both.json") << R"({"glint": 1, "image": {"width": 8, "height": 6},
    "camera": {"file": "cam.gltf", "eye": [0, 0, 1]}, "objects": []})";
  try {
    loadSceneFile(dir / "both.json");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("camera.eye: the camera comes from its file"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// Khronos' BoxWithInfinites: every vertex has an infinite coordinate, so
// every triangle is dropped; the scene says so, naming the file.
TEST(MeshImport, AModelWithNothingFiniteIsNamed) {
  const fs::path dir = fs::temp_directory_path() / "glint_gltf_infinites";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(kModels / "glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", dir / "box.glb");
  std::ofstream(dir / "scene.json") << R"({"glint": 1, "image": {"width": 8, "height": 6},
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, "lights": [{"type": "point", "position": [0, 5, 5]}],
    "objects": [{"type": "mesh", "file": "box.glb"}]})";
  const Scene s = loadSceneFile(dir / "scene.json");
  EXPECT_TRUE(s.geometry.triangles().empty());
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("objects[0] ('box.glb'): all "), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("nothing of this mesh can be seen"), std::string::npos) << s.warnings[0];
  fs::remove_all(dir);
}

// Through a bundle (what a server gets) the scene is the one loaded from
// disk, and the bundle holds the imported mesh, not the .gltf, .bin or .png.
TEST(MeshImport, ServersGetTheImportedMeshNotItsFiles) {
  const fs::path dir = fs::temp_directory_path() / "glint_mesh_bundle";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy(kModels / "glTF2/BoxTextured-glTF", dir / "box", fs::copy_options::recursive);
  nlohmann::json scene = nlohmann::json::parse(R"({"glint": 1, "image": {"width": 8, "height": 6},
    "camera": {"eye": [2, 2, 3], "look_at": [0, 0, 0]}, "lights": [{"type": "point", "position": [0, 5, 5]}],
    "objects": [{"type": "mesh", "file": "box/BoxTextured.gltf"}]})");
  std::ofstream(dir / "scene.json") << scene.dump();
  const proto::LoadedBundle loaded = proto::loadSceneBundle(dir / "scene.json");
  ASSERT_EQ(loaded.bundle.files.size(), 1u);
  const std::string& blob = loaded.bundle.files.at("box/BoxTextured.gltf");
  EXPECT_EQ(blob.substr(0, 8), "GLINTMSH");
  SceneBudget budget;
  const Scene there = proto::loadBundle(loaded.bundle, budget);
  const Scene& here = loaded.scene;
  EXPECT_EQ(there.geometry.positions(), here.geometry.positions());
  EXPECT_EQ(there.geometry.normals(), here.geometry.normals());
  EXPECT_EQ(there.geometry.uvs(), here.geometry.uvs());
  ASSERT_EQ(there.textures.size(), 1u);
  EXPECT_EQ(there.textures[0].image->rgb, here.textures[0].image->rgb);
  ASSERT_EQ(there.materials.size(), here.materials.size());
  for (std::size_t i = 0; i < here.materials.size(); ++i) {
    EXPECT_EQ(there.materials[i].color, here.materials[i].color);
    EXPECT_EQ(there.materials[i].texture, here.materials[i].texture);
  }

  // The .gltf itself sent in the blob's place is refused: no importer runs
  // on what a peer sends.
  proto::SceneBundle raw = loaded.bundle;
  std::ifstream in(dir / "box/BoxTextured.gltf");
  raw.files["box/BoxTextured.gltf"].assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  try {
    proto::loadBundle(raw, budget);
    ADD_FAILURE() << "a server loaded a raw glTF";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("glintd does not run importers"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// Every truncation of a blob, and counts that announce more than is there,
// are refused with an InputError before anything is allocated for them.
TEST(MeshImport, DamagedBlobsAreRefused) {
  const MeshModel box = import(kModels / "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb");
  const std::string blob = encodeMeshBlob(box);
  SceneBudget budget;
  const MeshModel back = decodeMeshBlob(blob, "test", budget);
  EXPECT_EQ(corners(back), corners(box));
  ASSERT_EQ(back.textures.size(), 1u);
  EXPECT_EQ(back.textures[0].wrap, box.textures[0].wrap);
  EXPECT_EQ(back.textures[0].filter, box.textures[0].filter);
  for (std::size_t n = 0; n < blob.size(); n += std::max<std::size_t>(1, blob.size() / 4000)) {
    SceneBudget fresh;
    EXPECT_THROW(decodeMeshBlob(std::string_view(blob).substr(0, n), "test", fresh), InputError) << n;
  }
  std::string huge = blob;
  const std::uint32_t lots = 0xfffffff0u;
  std::memcpy(huge.data() + 12, &lots, 4);  // the texture count
  SceneBudget fresh;
  EXPECT_THROW(decodeMeshBlob(huge, "test", fresh), InputError);
  std::string extra = blob + "x";
  EXPECT_THROW(decodeMeshBlob(extra, "test", fresh), InputError);
}

// The fuzzer's first find (tests/fuzz/corpus/mesh_blob/regression-empty-arrays):
// a mesh of no vertices decodes as one, without copying from nothing.
TEST(MeshImport, BlobWithEmptyArraysDecodes) {
  MeshModel empty;
  empty.materials.push_back(Material{});
  empty.meshes.push_back(MeshInput{});
  SceneBudget budget;
  const MeshModel back = decodeMeshBlob(encodeMeshBlob(empty), "test", budget);
  ASSERT_EQ(back.meshes.size(), 1u);
  EXPECT_TRUE(back.meshes[0].positions.empty());
  EXPECT_TRUE(back.meshes[0].indices.empty());
}

TEST(MeshImport, OtherExtensionsAreNamed) {
  MemorySource files;
  SceneBudget budget;
  try {
    importMeshFile(files, "car.fbx", "objects[0].file", budget, true);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("objects[0].file: 'car.fbx': mesh files are .obj, .ply, .gltf, .glb"),
              std::string::npos)
        << e.what();
  }
}

// glTF extensions: a Draco-compressed mesh (which Assimp renders as black
// blobs) is an error naming the extension; extensions Glint does not apply
// are named in one warning, the model rendered without them.
TEST(MeshImport, GltfExtensionsAreNamedNotDropped) {
  const fs::path draco = kModels / "glTF2/draco/2CylinderEngine.gltf";
  if (!fs::exists(draco)) GTEST_SKIP() << "assimp-testmodels is not installed";
  try {
    import(draco);
    FAIL() << "a Draco-compressed mesh was imported";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("test: '2CylinderEngine.gltf': uses KHR_draco_mesh_compression"),
              std::string::npos)
        << e.what();
  }
  const MeshModel clearcoat = import(kModels / "glTF2/ClearCoat-glTF/ClearCoatTest.gltf");
  ASSERT_EQ(clearcoat.warnings.size(), 1u);
  EXPECT_EQ(clearcoat.warnings[0],
            "'ClearCoatTest.gltf' uses glTF extensions Glint does not apply (KHR_materials_clearcoat): rendered "
            "without them");
  EXPECT_GT(triangles(clearcoat), 0u);
  for (const std::string& w : import(kModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf").warnings) {
    EXPECT_EQ(w.find("glTF extensions"), std::string::npos) << w;  // it uses none
  }
}

// Imported materials get Phong terms of their own (docs/scene-format.md):
// ambient 0.1 and diffuse 0.9 (a shadowed side is not black), and a
// highlight from the glTF roughness: r_S = 0.5 (1 - roughness), h = 2 / a^2
// - 2 with a = roughness^2 (clamped to [1, 1000]).
TEST(MeshImport, ImportedMaterialsGetAmbientAndAHighlightFromRoughness) {
  const fs::path rough = kModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf";  // roughness 1 (glTF's default)
  const fs::path half = kModels / "glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf";  // 0.5
  if (!fs::exists(rough) || !fs::exists(half)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const Material& box = import(rough).materials.at(0);
  EXPECT_FLOAT_EQ(box.ambient, 0.1f);
  EXPECT_FLOAT_EQ(box.diffuse, 0.9f);
  EXPECT_FLOAT_EQ(box.specular, 0.0f);
  const MeshModel cube = import(half);
  const Material& m = cube.materials.at(0);
  EXPECT_FLOAT_EQ(m.ambient, 0.1f);
  EXPECT_FLOAT_EQ(m.specular, 0.25f);
  EXPECT_FLOAT_EQ(m.shininess, 30.0f);  // a = 0.25: 2 / 0.0625 - 2
  EXPECT_NEAR(m.color.r, 0.6038274f, 1e-6);
}

// KHR_lights_punctual: a scene's mesh with "lights": true takes the file's
// point, spot and directional lights, placed by their nodes (a parent's
// matrix too) and the mesh's transform; a server gets the same lights from
// the blob. Without the flag the scene keeps its own lights only.
TEST(MeshImport, GltfLightsComeWithTheMeshWhenAsked) {
  const fs::path box = kModels / "glTF2/BoxTextured-glTF";
  if (!fs::exists(box)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const fs::path dir = fs::temp_directory_path() / "glint_gltf_lights";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy(box, dir / "box", fs::copy_options::recursive);
  nlohmann::json gltf = nlohmann::json::parse(std::ifstream(dir / "box/BoxTextured.gltf"));
  gltf["extensionsUsed"] = {"KHR_lights_punctual"};
  gltf["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 4.0}},
      {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
      {{"type", "directional"}, {"intensity", 2.0}}};
  // Node 0 (the box's parent) turns +Y to -Z; a point light child 2 above it
  // in its frame; a spot at (0, 3, 0) looking down; a sun along -X.
  gltf["nodes"][0]["children"].push_back(2);
  gltf["nodes"].push_back({{"translation", {0, 2, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  gltf["nodes"].push_back({{"translation", {0, 3, 0}},
                           {"rotation", {-0.70710678, 0, 0, 0.70710678}},
                           {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  gltf["nodes"].push_back({{"rotation", {0, 0.70710678, 0, 0.70710678}},
                           {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  gltf["scenes"][0]["nodes"] = {0, 3, 4};
  std::ofstream(dir / "box/BoxTextured.gltf") << gltf.dump();
  nlohmann::json scene = nlohmann::json::parse(R"({"glint": 1, "image": {"width": 8, "height": 6},
    "camera": {"eye": [2, 2, 3], "look_at": [0, 0, 0]}, "lights": [{"type": "point", "position": [0, 5, 5]}],
    "objects": [{"type": "mesh", "file": "box/BoxTextured.gltf", "lights": true,
                 "transform": {"translate": [10, 0, 0]}}]})");
  std::ofstream(dir / "scene.json") << scene.dump();
  const proto::LoadedBundle loaded = proto::loadSceneBundle(dir / "scene.json");
  const std::vector<Light>& lights = loaded.scene.lights;
  ASSERT_EQ(lights.size(), 4u);
  EXPECT_EQ(lights[1].type, LightType::kPoint);
  EXPECT_NEAR(glm::length(lights[1].position - glm::vec3(10, 0, -2)), 0.0f, 1e-5f);  // +Y turned to -Z
  EXPECT_EQ(lights[1].color, glm::vec3(4.0f, 2.0f, 1.0f));
  EXPECT_EQ(lights[1].attenuation, glm::vec3(0, 0, 1));
  EXPECT_EQ(lights[2].type, LightType::kSpot);
  EXPECT_NEAR(glm::length(lights[2].position - glm::vec3(10, 3, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(lights[2].direction - glm::vec3(0, -1, 0)), 0.0f, 1e-5f);
  EXPECT_FLOAT_EQ(lights[2].cosInner, std::cos(0.2f));
  EXPECT_FLOAT_EQ(lights[2].cosOuter, std::cos(0.5f));
  EXPECT_EQ(lights[3].type, LightType::kDirectional);
  EXPECT_NEAR(glm::length(lights[3].direction - glm::vec3(-1, 0, 0)), 0.0f, 1e-5f);
  EXPECT_EQ(lights[3].color, glm::vec3(2.0f));
  SceneBudget budget;
  const Scene there = proto::loadBundle(loaded.bundle, budget);
  ASSERT_EQ(there.lights.size(), lights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) {
    EXPECT_EQ(there.lights[i].type, lights[i].type);
    EXPECT_EQ(there.lights[i].position, lights[i].position);
    EXPECT_EQ(there.lights[i].direction, lights[i].direction);
    EXPECT_EQ(there.lights[i].color, lights[i].color);
    EXPECT_EQ(there.lights[i].cosOuter, lights[i].cosOuter);
  }
  scene["objects"][0].erase("lights");
  std::ofstream(dir / "scene.json") << scene.dump();
  EXPECT_EQ(proto::loadSceneBundle(dir / "scene.json").scene.lights.size(), 1u);
  fs::remove_all(dir);
}

// A light the file names wrongly is an error that says where.
TEST(MeshImport, BadGltfLightsAreNamed) {
  const fs::path box = kModels / "glTF2/BoxTextured-glTF";
  if (!fs::exists(box)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const fs::path dir = fs::temp_directory_path() / "glint_gltf_bad_lights";
  fs::remove_all(dir);
  fs::copy(box, dir, fs::copy_options::recursive);
  nlohmann::json gltf = nlohmann::json::parse(std::ifstream(dir / "BoxTextured.gltf"));
  gltf["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "area"}}};
  gltf["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 0;
  std::ofstream(dir / "BoxTextured.gltf") << gltf.dump();
  try {
    import(dir / "BoxTextured.gltf");
    ADD_FAILURE() << "an unknown light type was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("node 1's KHR_lights_punctual light: its type is not point, spot or directional"),
              std::string::npos)
        << e.what();
  }
  gltf["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 5;
  std::ofstream(dir / "BoxTextured.gltf") << gltf.dump();
  EXPECT_THROW(import(dir / "BoxTextured.gltf"), InputError);
  fs::remove_all(dir);
}

// Numbers a double holds but a float does not (1e39, 1e308), or that are
// negative where light is: each refused naming what, by the importer as by a
// server reading the blob (the same check on both paths): before, glint
// rendered them black while glintd refused the scene.
TEST(MeshImport, GltfNumbersBeyondAFloatOrNegativeAreRefused) {
  const fs::path box = kModels / "glTF2/BoxTextured-glTF";
  if (!fs::exists(box)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const fs::path dir = fs::temp_directory_path() / "glint_gltf_overflow";
  const nlohmann::json light = {{"type", "point"}};
  struct Case {
    std::function<void(nlohmann::json&)> edit;
    const char* says;
  };
  const std::vector<Case> cases = {
      {[&](nlohmann::json& g) { g["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = 1e39; },
       "intensity is beyond a float's range"},
      {[&](nlohmann::json& g) { g["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = 1e308; },
       "intensity is beyond a float's range"},
      {[&](nlohmann::json& g) { g["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = -2; },
       "its color and intensity must not be negative"},
      {[&](nlohmann::json& g) {
         g["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = 3e38;
         g["extensions"]["KHR_lights_punctual"]["lights"][0]["color"] = {2, 1, 1};
       },
       "its color times its intensity is beyond a float's range"},
      {[&](nlohmann::json& g) {  // a light 1e38 along a parent scaled by 1e38
         g["nodes"][1].erase("extensions");
         const std::size_t parent = g["nodes"].size();
         g["nodes"].push_back({{"matrix", {1e38, 0, 0, 0, 0, 1e38, 0, 0, 0, 0, 1e38, 0, 0, 0, 0, 1}},
                               {"children", {parent + 1}}});
         g["nodes"].push_back({{"translation", {1e38, 0, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
       },
       "its node's transform is beyond a float's range"},
      {[&](nlohmann::json& g) { g["materials"][0]["emissiveFactor"] = {-1, 0, 0}; },
       "has a colour or emission that is negative or beyond a float's range"},
  };
  for (const Case& c : cases) {
    fs::remove_all(dir);
    fs::copy(box, dir, fs::copy_options::recursive);
    nlohmann::json gltf = nlohmann::json::parse(std::ifstream(dir / "BoxTextured.gltf"));
    gltf["extensions"]["KHR_lights_punctual"]["lights"] = {light};
    gltf["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 0;
    c.edit(gltf);
    std::ofstream(dir / "BoxTextured.gltf") << gltf.dump();
    try {
      import(dir / "BoxTextured.gltf");
      ADD_FAILURE() << "taken: " << c.says;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
    }
  }
  fs::remove_all(dir);
}

// glTF's metallic-roughness: metallic x (1 - roughness) reflects, blurred
// by the roughness; the blob carries both to a server.
TEST(MeshImport, MetallicRoughnessGivesARoughReflection) {
  const fs::path box = kModels / "glTF2/BoxTextured-glTF";
  if (!fs::exists(box)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const fs::path dir = fs::temp_directory_path() / "glint_metal_box";
  fs::remove_all(dir);
  fs::copy(box, dir, fs::copy_options::recursive);
  nlohmann::json gltf = nlohmann::json::parse(std::ifstream(dir / "BoxTextured.gltf"));
  gltf["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 1.0;
  gltf["materials"][0]["pbrMetallicRoughness"]["roughnessFactor"] = 0.4;
  std::ofstream(dir / "BoxTextured.gltf") << gltf.dump();
  const MeshModel metal = import(dir / "BoxTextured.gltf");
  EXPECT_FLOAT_EQ(metal.materials.at(0).reflectivity, 0.6f);
  EXPECT_FLOAT_EQ(metal.materials.at(0).roughness, 0.4f);
  SceneBudget budget;
  const MeshModel there = decodeMeshBlob(encodeMeshBlob(metal), "test", budget);
  EXPECT_EQ(there.materials.at(0).roughness, metal.materials.at(0).roughness);
  EXPECT_EQ(there.materials.at(0).reflectivity, metal.materials.at(0).reflectivity);
  // A surface that does not reflect takes no roughness.
  EXPECT_EQ(import(box / "BoxTextured.gltf").materials.at(0).roughness, 0.0f);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace glint
