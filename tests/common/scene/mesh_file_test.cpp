// Mesh files as exporters write them: backslash paths, missing MTL files and
// textures (a warning, once), reflective MTL illumination models, materials
// renamed or traced per mesh, files that hold no triangle, and vertex
// normals smoothed up to a crease angle.
#include <sstream>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "common/base/error.h"
#include "common/base/file_source.h"
#include "common/scene/scene_load.h"
#include "common/scene/smooth_normals.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

using nlohmann::json;

// A scene with one material "m" and the given objects.
std::string sceneWith(const std::vector<json>& objects) {
  json j = json::parse(R"({
    "glint": 1, "image": {"width": 8, "height": 6},
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"m": {"color": [1, 0, 0]}, "mirror": {"reflectivity": 0.9}},
    "lights": [{"type": "point", "position": [0, 5, 5]}]
  })");
  j["objects"] = objects;
  return j.dump();
}

json meshFile(const char* file) { return {{"type", "mesh"}, {"file", file}}; }

std::string loadError(const std::string& text, MemorySource& files) {
  try {
    loadScene(text, files);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(loaded without error)";
}

const char* const kSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";

TEST(MeshFile, BackslashPathsAndMissingFilesAreWarningsOnce) {
  MemorySource files;
  files.add("models/a.obj", std::string("mtllib .\\\\mats\\\\a.mtl\n") + kSquare +
                                "usemtl tex\nf 1/1 2/2 3/3\nusemtl gone\nf 1/1 3/3 4/4\n");
  files.add("models/mats/a.mtl", "newmtl tex\nKd 0 1 0\nmap_Kd ..\\\\textures\\\\wall.png\n"
                                 "newmtl gone\nKd 0 0 1\nmap_Kd missing.png\n");
  files.add("models/b.obj", std::string("mtllib nowhere.mtl\n") + kSquare + "f 1 2 3\n");
  const unsigned char png1x1[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 0, 0,
                                  1, 0, 0, 0, 1, 8, 2, 0, 0, 0, 0x90, 0x77, 0x53, 0xde, 0, 0, 0, 12, 'I', 'D', 'A',
                                  'T', 0x08, 0xd7, 0x63, 0xf8, 0xcf, 0xc0, 0, 0, 0x03, 0x01, 0x01, 0x00, 0x18, 0xdd,
                                  0x8d, 0xb0, 0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  files.add("models/textures/wall.png", std::string(reinterpret_cast<const char*>(png1x1), sizeof png1x1));
  const Scene s = loadScene(sceneWith({meshFile("models/a.obj"), meshFile("models/a.obj"), meshFile("models/b.obj")}),
                            files);
  EXPECT_EQ(s.geometry.triangles().size(), 5u);
  ASSERT_EQ(s.warnings.size(), 2u);  // two objects use a.obj: its missing texture is said once
  EXPECT_EQ(s.warnings[0], "'models/mats/a.mtl' names the texture 'models/mats/missing.png' (map_Kd of material "
                          "gone), which is missing; the material's Kd colour is used");
  EXPECT_EQ(s.warnings[1], "'models/b.obj' names the material library 'models/nowhere.mtl', which is missing; its "
                          "faces get the default material");
  const auto named = [&s](const std::string& name) {
    for (const Material& m : s.materials) {
      if (m.name == name) return m;
    }
    ADD_FAILURE() << "no material " << name;
    return Material{};
  };
  EXPECT_GE(named("objects[0]:tex").texture, 0);  // found through ..\textures\wall.png
  EXPECT_EQ(named("objects[0]:gone").texture, -1);
  EXPECT_EQ(named("objects[0]:gone").color, glm::vec3(0, 0, 1));
}

// A corner reuses the vertex of an earlier corner of the same material with
// the same position, normal and uv, and only that; vertices come in the
// order of their first corners; a material with a corner lacking a normal
// gets face normals (none stored).
TEST(MeshFile, CornersShareVerticesOnlyWhereAllTheyNameIsTheSame) {
  MemorySource files;
  files.add("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\n"
                     "vn 0 0 1\nvn 0 1 0\nusemtl a\nf 1/1/1 2/2/1 3/3/1\nf 1/1/2 3/3/2 4/2/2\nusemtl b\n"
                     "f 1/1/1 2/2/1 5/3/1\nf 3 4 5\nusemtl a\nf 2/2/1 3/3/1 5/1/1\n");
  files.add("m.mtl", "newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\n");
  const Scene s = loadScene(sceneWith({meshFile("m.obj")}), files);
  ASSERT_EQ(s.geometry.triangles().size(), 5u);
  const auto corners = [&s](std::size_t t) {
    const auto& v = s.geometry.triangles()[t].v;
    return std::vector<std::uint32_t>{v[0], v[1], v[2]};
  };
  // Material a's mesh first (7 vertices: 1/1/1 and 1/1/2 differ by normal),
  // then b's (6), in the geometry's shared vertex list.
  EXPECT_EQ(corners(0), (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(corners(1), (std::vector<std::uint32_t>{3, 4, 5}));
  EXPECT_EQ(corners(2), (std::vector<std::uint32_t>{1, 2, 6}));
  EXPECT_EQ(corners(3), (std::vector<std::uint32_t>{7, 8, 9}));
  EXPECT_EQ(corners(4), (std::vector<std::uint32_t>{10, 11, 12}));
  EXPECT_EQ(s.geometry.positions().size(), 13u);
  EXPECT_EQ(s.geometry.normals()[3], glm::vec3(0, 1, 0));
  EXPECT_EQ(s.geometry.normals()[7], glm::vec3(0));  // b lacks some normals: face normals
}

// A mesh's uvs begin with its first corner that has one: the vertices
// before it get (0, 0), as do later corners without one.
TEST(MeshFile, VerticesBeforeTheFirstUvGetZero) {
  MemorySource files;
  files.add("u.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0.25 0.5\nvt 0.75 1\n"
                     "f 1 2 3\nf 1/1 3/2 4/2\nf 2 4 3\n");
  const Scene s = loadScene(sceneWith({meshFile("u.obj")}), files);
  // 1 2 3; 1/1 3/2 4/2, each a new corner; 2 and 3 as before, 4 without uv new.
  ASSERT_EQ(s.geometry.uvs().size(), 7u);
  const std::vector<glm::vec2> expected = {glm::vec2(0), glm::vec2(0), glm::vec2(0), {0.25f, 0.5f},
                                           {0.75f, 1.0f}, {0.75f, 1.0f}, glm::vec2(0)};
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(s.geometry.uvs()[i], expected[i]) << "vertex " << i;
  ASSERT_EQ(s.geometry.triangles().size(), 3u);
  EXPECT_EQ(s.geometry.triangles()[2].v, (std::array<std::uint32_t, 3>{1, 2, 6}));
}

// The material library is the first mtllib line: after a comment naming
// another, indented, with Windows line ends.
TEST(MeshFile, MtllibIsFoundAsExportersWriteIt) {
  MemorySource files;
  files.add("m.obj", std::string("# mtllib wrong.mtl\r\n  mtllib  right.mtl  \r\n") + kSquare + "usemtl red\r\nf 1 2 3\r\n");
  files.add("right.mtl", "newmtl red\nKd 1 0 0\n");
  const Scene s = loadScene(sceneWith({meshFile("m.obj")}), files);
  EXPECT_TRUE(s.warnings.empty());
  EXPECT_EQ(s.materials[s.geometry.materialOf(0)].color, glm::vec3(1, 0, 0));
}

TEST(MeshFile, ReflectiveIlluminationModelsGiveReflectivity) {
  MemorySource files;
  files.add("a.obj", std::string("mtllib a.mtl\n") + kSquare + "usemtl shiny\nf 1 2 3\nusemtl matte\nf 1 3 4\n");
  files.add("a.mtl", "newmtl shiny\nillum 3\nKs 0.6 0.6 0.9\nNs 200\nnewmtl matte\nillum 2\nKs 0.6 0.6 0.9\n");
  const Scene s = loadScene(sceneWith({meshFile("a.obj")}), files);
  ASSERT_EQ(s.materials.size(), 4u);
  EXPECT_FLOAT_EQ(s.materials[2].reflectivity, 0.7f);
  EXPECT_FLOAT_EQ(s.materials[3].reflectivity, 0.0f);  // illum 2: Ks is the highlight only
  EXPECT_FLOAT_EQ(s.materials[3].specular, 0.7f);
}

TEST(MeshFile, MaterialsRenamedOrTracedPerMesh) {
  MemorySource files;
  files.add("a.obj", std::string("mtllib a.mtl\n") + kSquare + "usemtl red\nf 1 2 3\nusemtl blue\nf 1 3 4\n");
  files.add("a.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n");
  json renamed = meshFile("a.obj");
  renamed["materials"] = {{"blue", "mirror"}};
  renamed["raytrace"] = true;
  json traced = {{"type", "mesh"}, {"positions", {0, 0, 0, 1, 0, 0, 0, 1, 0}}, {"indices", {0, 1, 2}},
                 {"material", "m"}, {"raytrace", true}};
  const Scene s = loadScene(sceneWith({renamed, traced}), files);
  ASSERT_EQ(s.geometry.triangles().size(), 3u);
  // m and mirror as the scene says; red from the file, traced; mirror and m copied, traced.
  EXPECT_EQ(s.materials[0].raytrace, RaytraceRule::kAuto);
  EXPECT_EQ(s.materials[1].raytrace, RaytraceRule::kAuto);
  for (std::uint32_t t = 0; t < 3; ++t) {
    const Material& m = s.materials[s.geometry.materialOf(t)];
    EXPECT_EQ(m.raytrace, RaytraceRule::kAlways) << m.name;
  }
  EXPECT_FLOAT_EQ(s.materials[s.geometry.materialOf(1)].reflectivity, 0.9f);  // blue -> mirror

  json unknown = meshFile("a.obj");
  unknown["materials"] = {{"green", "m"}};
  EXPECT_NE(loadError(sceneWith({unknown}), files).find("objects[0].materials.green: the file has no material named"),
            std::string::npos);
  unknown["materials"] = {{"red", "gold"}};
  EXPECT_NE(loadError(sceneWith({unknown}), files).find("objects[0].materials.red: no material named 'gold'"),
            std::string::npos);
  unknown["material"] = "m";
  EXPECT_NE(loadError(sceneWith({unknown}), files).find("objects[0].materials: renames"), std::string::npos);
}

TEST(MeshFile, FilesWithoutTrianglesAreErrors) {
  MemorySource files;
  files.add("empty.obj", "\n  \n");
  files.add("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\nl 1 2\n");
  const std::string utf16("\xff\xfe" "v\0 \0" "0\0", 8);
  files.add("utf16.obj", utf16);
  const std::pair<const char*, const char*> cases[] = {
      {"empty.obj", "objects[0].file: 'empty.obj' is empty"},
      {"points.obj", "objects[0].file: 'points.obj' holds no triangle (3 vertices, no faces"},
      {"utf16.obj", "objects[0].file: 'utf16.obj' is not a text file in ASCII or UTF-8 (UTF-16"},
  };
  for (const auto& [file, message] : cases) {
    json mesh = meshFile(file);
    mesh["material"] = "m";
    const std::string error = loadError(sceneWith({mesh}), files);
    EXPECT_NE(error.find(message), std::string::npos) << error;
  }
}

// Two triangles folded at a right angle along their shared edge: below the
// crease angle each keeps its face normal, above it the shared vertices get
// the mean of the two (equal areas), the others their face's.
TEST(MeshFile, SmoothNormalsCreaseAtTheAngle) {
  const MeshInput folded{{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, {}, {}, {0, 1, 2, 0, 3, 1}, 0, {}};
  const glm::vec3 down(0, 1, 0), side(1, 0, 0);  // the faces' normals by their winding
  MeshInput sharp = folded;
  smoothNormals(sharp, 60.0f);
  ASSERT_EQ(sharp.indices.size(), 6u);
  EXPECT_EQ(sharp.positions.size(), 6u);  // the shared edge's vertices split
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(sharp.normals[sharp.indices[static_cast<std::size_t>(c)]], down);
    EXPECT_EQ(sharp.normals[sharp.indices[static_cast<std::size_t>(3 + c)]], side);
  }
  MeshInput smooth = folded;
  smoothNormals(smooth, 100.0f);
  EXPECT_EQ(smooth.positions.size(), 4u);
  const glm::vec3 mean = glm::normalize(down + side);
  for (const std::uint32_t shared : {0u, 1u}) EXPECT_LT(glm::length(smooth.normals[shared] - mean), 1e-6f);
  EXPECT_EQ(smooth.normals[2], down);
  EXPECT_EQ(smooth.normals[3], side);
  EXPECT_EQ(smooth.positions, folded.positions);
}

TEST(MeshFile, SmoothKeyGivesNormalsOnlyWhereTheFileHasNone) {
  MemorySource files;
  files.add("plain.obj", std::string(kSquare) + "f 1 2 3\nf 1 3 4\n");
  files.add("normals.obj", std::string(kSquare) + "vn 0 0.6 0.8\nf 1//1 2//1 3//1\n");
  json plain = meshFile("plain.obj"), given = meshFile("normals.obj");
  plain["smooth"] = given["smooth"] = 45;
  plain["material"] = given["material"] = "m";
  const Scene s = loadScene(sceneWith({plain, given}), files);
  ASSERT_EQ(s.geometry.triangles().size(), 3u);
  const auto normal = [&s](std::size_t t) { return s.geometry.normals()[s.geometry.triangles()[t].v[0]]; };
  EXPECT_EQ(normal(0), glm::vec3(0, 0, 1));  // smoothed: the square is flat
  EXPECT_EQ(normal(2), glm::vec3(0, 0.6f, 0.8f));  // the file's own
  json bad = plain;
  bad["smooth"] = 200;
  EXPECT_NE(loadError(sceneWith({bad}), files).find("objects[0].smooth"), std::string::npos);
}

// The bunny's own normals are area-weighted means of its face normals
// (scenes/models/README.md): with its normals stripped, "smooth": 180 gives
// them back at every corner.
TEST(MeshFile, SmoothedBunnyHasItsOwnNormalsBack) {
  DirectorySource disk(test::sourcePath("scenes/models"), std::size_t{1} << 26);
  const std::string obj = disk.read("bunny.obj", "test");
  std::istringstream lines(obj);
  std::string stripped;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("vn ", 0) == 0) continue;
    if (line.rfind("f ", 0) == 0) {
      std::istringstream words(line.substr(2));
      line = "f";
      for (std::string corner; words >> corner;) line += " " + corner.substr(0, corner.find('/'));
    }
    stripped += line + "\n";
  }
  MemorySource files;
  files.add("own.obj", obj);
  files.add("stripped.obj", stripped);
  json own = meshFile("own.obj"), smooth = meshFile("stripped.obj");
  own["material"] = smooth["material"] = "m";
  smooth["smooth"] = 180;
  const Scene a = loadScene(sceneWith({own}), files), b = loadScene(sceneWith({smooth}), files);
  ASSERT_EQ(a.geometry.triangles().size(), b.geometry.triangles().size());
  float worst = 0.0f;
  for (std::size_t t = 0; t < a.geometry.triangles().size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 na = a.geometry.normals()[a.geometry.triangles()[t].v[static_cast<std::size_t>(k)]];
      const glm::vec3 nb = b.geometry.normals()[b.geometry.triangles()[t].v[static_cast<std::size_t>(k)]];
      worst = std::max(worst, glm::length(na - nb));
    }
  }
  EXPECT_LT(worst, 2e-3f);  // the file's normals are written with 6 digits
}

}  // namespace
}  // namespace glint
