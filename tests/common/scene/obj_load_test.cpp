// loadObj reads triangles and quads through tinyobjloader's callback
// interface and larger polygons through its LoadObj: these tests hold the
// result to what LoadObj itself makes of the same files (triangle by
// triangle, bit by bit), to the geometry a triangulation must have (a
// quad's shorter diagonal, a concave polygon's area), and to the errors a
// bad face or a limit gives.
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>

#include <gtest/gtest.h>
#include <tiny_obj_loader.h>

#include "common/base/error.h"
#include "common/base/file_source.h"
#include "common/scene/obj_colors.h"
#include "common/scene/obj_faces.h"
#include "common/scene/obj_load.h"

namespace glint {
namespace {

// A triangle's three corners: position, normal (zero where the mesh has
// none) and uv, eight floats each.
using Triangle = std::array<float, 24>;
// The triangles of each material (its index; the default one last), in
// file order.
using Soup = std::map<int, std::vector<Triangle>>;

MeshModel load(const std::string& obj, const std::string& mtl = "", LoadLimits limits = {}) {
  MemorySource files;
  files.add("m.obj", obj);
  if (!mtl.empty()) files.add("m.mtl", mtl);
  SceneBudget budget(limits);
  return loadObj(files, "m.obj", "test", budget, true);
}

std::string loadError(const std::string& obj, LoadLimits limits = {}) {
  try {
    load(obj, "", limits);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(loaded without error)";
}

Soup soupOf(const MeshModel& model) {
  Soup soup;
  for (const MeshInput& mesh : model.meshes) {
    for (std::size_t t = 0; t < mesh.indices.size() / 3; ++t) {
      Triangle tri{};
      for (std::size_t k = 0; k < 3; ++k) {
        const std::uint32_t i = mesh.indices[3 * t + k];
        const glm::vec3 n = mesh.normals.empty() ? glm::vec3(0.0f) : mesh.normals[i];
        const glm::vec2 uv = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[i];  // absent: (0, 0)
        const float corner[8] = {mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z, n.x, n.y, n.z, uv.x,
                                 uv.y};
        std::memcpy(&tri[8 * k], corner, sizeof corner);
      }
      soup[static_cast<int>(mesh.material)].push_back(tri);
    }
  }
  return soup;
}

// The same file read by tinyobjloader's LoadObj (triangulating): faces
// without a known material go to the default one after the MTL's, and a
// material some of whose corners lack a normal has none (loadObj's rule).
Soup loadObjSoup(const std::string& obj, const std::string& mtl) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  EXPECT_TRUE(reader.ParseFromString(obj, mtl, config)) << reader.Error();
  const tinyobj::attrib_t& a = reader.GetAttrib();
  const int fallback = static_cast<int>(reader.GetMaterials().size());
  Soup soup;
  std::map<int, bool> lacksNormal;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const int id = shape.mesh.material_ids[f];
      const int material = id >= 0 && id < fallback ? id : fallback;
      Triangle tri{};
      for (std::size_t k = 0; k < 3; ++k) {
        const tinyobj::index_t c = shape.mesh.indices[3 * f + k];
        float* corner = &tri[8 * k];
        for (int axis = 0; axis < 3; ++axis) corner[axis] = a.vertices[3 * c.vertex_index + axis];
        for (int axis = 0; axis < 3 && c.normal_index >= 0; ++axis)
          corner[3 + axis] = a.normals[3 * c.normal_index + axis];
        for (int axis = 0; axis < 2 && c.texcoord_index >= 0; ++axis)
          corner[6 + axis] = a.texcoords[2 * c.texcoord_index + axis];
        lacksNormal[material] = lacksNormal[material] || c.normal_index < 0;
      }
      soup[material].push_back(tri);
    }
  }
  for (auto& [material, triangles] : soup) {
    for (Triangle& tri : triangles) {
      for (std::size_t k = 0; k < 3 && lacksNormal[material]; ++k)
        std::fill_n(&tri[8 * k + 3], 3, 0.0f);
    }
  }
  return soup;
}

void expectAsLoadObj(const std::string& obj, const std::string& mtl) {
  const Soup expected = loadObjSoup(obj, mtl);
  const Soup got = soupOf(load(obj, mtl));
  ASSERT_EQ(got.size(), expected.size());
  for (const auto& [material, triangles] : expected) {
    ASSERT_EQ(got.count(material), 1u) << "material " << material;
    const std::vector<Triangle>& mine = got.at(material);
    ASSERT_EQ(mine.size(), triangles.size()) << "material " << material;
    for (std::size_t t = 0; t < mine.size(); ++t) {
      EXPECT_EQ(std::memcmp(mine[t].data(), triangles[t].data(), sizeof(Triangle)), 0)
          << "material " << material << " triangle " << t;
    }
  }
}

const char* const kMtl =
    "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\nnewmtl red\nKd 0 1 0\n";  // a second "red": the
                                                                            // first counts

// Triangles and quads (split both ways), relative indices, normals and uvs
// on some corners only, groups and objects, usemtl before the mtllib line,
// with trailing words, and of a material the MTL lacks.
TEST(ObjLoad, TrianglesAndQuadsAsLoadObjReadsThem) {
  const std::string obj =
      "usemtl blue\nv -2 0 0\nv 0 -1 0\nv 2 0 0\nv 0 1 0\nf 1 2 3 4\n"
      "mtllib m.mtl\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\nvn 0 1 0\n"
      "o first\nusemtl red\nf 2/1/1 3/2/1 4/3/1 1/1/1\nf -4/-3/-2 -3/-2/-1 -2/-1/-1\n"
      "g side part\nusemtl  blue  shiny\nv 0 0 3\nv 1 0 3\nv 1 1 3.5\nv 0 1 3.25\nf -4 -3 -2 -1\nf "
      "5/1 6/2 7/3\n"
      "usemtl gold\nf 1//2 2//2 5//1\nf 1 2\nusemtl red\nf 8/3/2 7/2/2 6/1/1 5/1/1\n";
  expectAsLoadObj(obj, kMtl);
  EXPECT_EQ(soupOf(load(obj, kMtl)).at(0).size(), 5u);  // red: two quads and a triangle
}

// A pentagon goes through LoadObj's ear clipping, and its file's quads and
// triangles come out as the callbacks would give them.
TEST(ObjLoad, FilesWithLargerPolygonsAsLoadObjReadsThem) {
  const std::string obj =
      "mtllib m.mtl\nv 0 0 0\nv 4 0 0\nv 4 4 0\nv 2 1 0\nv 0 4 0\nvn 0 0 1\n"
      "usemtl blue\nf 1//1 2//1 3//1 4//1 5//1\nusemtl red\nf 1 2 3 4\nf 1 3 5\n";
  expectAsLoadObj(obj, kMtl);
}

double area(const Triangle& t) {
  const double ux = t[8] - t[0], uy = t[9] - t[1], vx = t[16] - t[0], vy = t[17] - t[1];
  return std::abs(ux * vy - uy * vx) / 2.0;
}

bool hasCorner(const Triangle& t, float x, float y) {
  for (std::size_t k = 0; k < 3; ++k) {
    if (t[8 * k] == x && t[8 * k + 1] == y) return true;
  }
  return false;
}

// A rhombus 4 wide and 2 high is split along its short diagonal, (0,-1) to
// (0,1), whichever corner the face starts at.
TEST(ObjLoad, QuadsSplitAlongTheShorterDiagonal) {
  for (const char* face : {"f 1 2 3 4\n", "f 2 3 4 1\n"}) {
    const Soup soup = soupOf(load(std::string("v -2 0 0\nv 0 -1 0\nv 2 0 0\nv 0 1 0\n") + face));
    ASSERT_EQ(soup.at(0).size(), 2u) << face;
    for (const Triangle& t : soup.at(0)) {
      EXPECT_TRUE(hasCorner(t, 0, -1) && hasCorner(t, 0, 1)) << face;
      EXPECT_EQ(area(t), 2.0) << face;
    }
  }
}

// The pentagon (0,0) (4,0) (4,4) (2,1) (0,4) has area 10; a fan from its
// first corner would cover 14 (a triangle outside it). Ear clipping covers
// exactly the polygon.
TEST(ObjLoad, ConcavePolygonsAreEarClipped) {
  const Soup soup = soupOf(load("v 0 0 0\nv 4 0 0\nv 4 4 0\nv 2 1 0\nv 0 4 0\nf 1 2 3 4 5\n"));
  ASSERT_EQ(soup.at(0).size(), 3u);
  double covered = 0.0;
  for (const Triangle& t : soup.at(0)) covered += area(t);
  EXPECT_EQ(covered, 10.0);
}

// A negative index counts back from the last vertex read before the face.
TEST(ObjLoad, NegativeIndicesCountBackFromTheFace) {
  const Soup soup = soupOf(
      load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 0 0\nv 6 0 0\nv 5 1 0\nf -3 -2 -1\n"));
  ASSERT_EQ(soup.at(0).size(), 2u);
  EXPECT_TRUE(hasCorner(soup.at(0)[0], 0, 0) && hasCorner(soup.at(0)[0], 1, 0) &&
              hasCorner(soup.at(0)[0], 0, 1));
  EXPECT_TRUE(hasCorner(soup.at(0)[1], 5, 0) && hasCorner(soup.at(0)[1], 6, 0) &&
              hasCorner(soup.at(0)[1], 5, 1));
}

TEST(ObjLoad, FacesNamingMissingDataAreErrors) {
  const std::string has =
      " refers to a vertex, normal or uv that the file does not have (it has 3 vertices, ";
  const std::pair<const char*, std::string> cases[] = {
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n",
       "test: 'm.obj' face 2" + has + "0 normals, 0 uvs)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "test: 'm.obj' face 1" + has},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n", "test: 'm.obj' face 1" + has},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n",
       "test: 'm.obj' face 1" + has + "1 normals, 0 uvs)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/-2 2/1 3/1\n",
       "test: 'm.obj' face 1" + has + "0 normals, 1 uvs)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 9\n", "test: 'm.obj' face 1" + has},
      // as LoadObj triangulated the pentagon: its third triangle
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4 9\n",
       "test: 'm.obj' triangle 3 refers to a vertex, normal or uv that the file does not have (it "
       "has 4 vertices"},
  };
  for (const auto& [obj, message] : cases) {
    const std::string error = loadError(obj);
    EXPECT_NE(error.find(message), std::string::npos) << obj << "\n" << error;
  }
}

// Faces of one or two corners are dropped, as LoadObj drops them.
TEST(ObjLoad, FacesOfFewerThanThreeCornersAreDropped) {
  const Soup soup = soupOf(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1\nf 1 2\nf 1 2 3\n"));
  EXPECT_EQ(soup.at(0).size(), 1u);
}

TEST(ObjLoad, LimitsStopTheParse) {
  LoadLimits limits;
  limits.maxTriangles = 1;
  EXPECT_NE(loadError("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\n", limits)
                .find("test: 'm.obj' has more triangles than the limit of 1"),
            std::string::npos);
  limits = {};
  limits.maxVertices = 2;
  EXPECT_NE(loadError("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", limits)
                .find("test: 'm.obj' has 3 vertices, over the limit of 2"),
            std::string::npos);
}

void expectSame(const ObjTriangles& a, const ObjTriangles& b, const std::string& what) {
  EXPECT_EQ(a.attrib.vertices, b.attrib.vertices) << what;
  EXPECT_EQ(a.attrib.normals, b.attrib.normals) << what;
  EXPECT_EQ(a.attrib.texcoords, b.attrib.texcoords) << what;
  ASSERT_EQ(a.corners.size(), b.corners.size()) << what;
  for (std::size_t i = 0; i < a.corners.size(); ++i) {
    EXPECT_TRUE(a.corners[i].vertex_index == b.corners[i].vertex_index &&
                a.corners[i].normal_index == b.corners[i].normal_index &&
                a.corners[i].texcoord_index == b.corners[i].texcoord_index)
        << what << ", corner " << i;
  }
  EXPECT_EQ(a.materialOf, b.materialOf) << what;
  ASSERT_EQ(a.materials.size(), b.materials.size()) << what;
}

// usemtl lines before the mtllib line and after it, in whichever piece they
// fall, a material carried across a cut, an unknown one; no relative index.
const char* const kPieceText =
    "usemtl blue\nv -2 0 0\nv 0 -1 0\nv 2 0 0\nv 0 1 0\nf 1 2 3 4\nusemtl red\nf 1 2 3\nmtllib "
    "m.mtl\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\nvn 0 1 0\no first\nf 2 3 4\nusemtl red\nf 2/1/1 3/2/1 4/3/1 "
    "1/1/1\n"
    "g side part\nusemtl  blue  shiny\nv 0 0 3\nv 1 0 3\nv 1 1 3.5\nv 0 1 3.25\nf 5 6 7 8\nf 5/1 "
    "6/2 7/3\n"
    "usemtl gold\nf 1//2 2//2 5//1\nf 1 2\nusemtl red\nf 8/3/2 7/2/2 6/1/1 5/1/1\nf 1 2 3\nf 4 5 "
    "6\n"
    "usemtl blue\nf 4 5 6\nf 6 7 8\n";

// Read in 2 to 40 pieces (cut after every line somewhere), the text gives
// what one read gives.
TEST(ObjLoad, PiecesJoinAsOneRead) {
  expectAsLoadObj(kPieceText, kMtl);
  const ObjTriangles whole = parseObjTriangles(kPieceText, kMtl, {}, "test", 1);
  EXPECT_EQ(whole.pieces, 1u);
  EXPECT_EQ(whole.materialOf.size(), 16u);
  for (std::size_t pieces = 2; pieces <= 40; ++pieces) {
    const ObjTriangles split = parseObjTriangles(kPieceText, kMtl, {}, "test", pieces);
    EXPECT_GT(split.pieces, 1u) << pieces;
    expectSame(split, whole, std::to_string(pieces) + " pieces");
  }
}

// A relative index in a later piece needs the vertices before it: such a
// file, a file with an error in a later piece, and one whose pieces
// together pass a limit are read again whole, with one read's result.
TEST(ObjLoad, PiecesThatCannotJoinAreReadWhole) {
  const std::string relative = std::string(kPieceText) + "f -3 -2 -1\n";
  const ObjTriangles whole = parseObjTriangles(relative, kMtl, {}, "test", 1);
  for (std::size_t pieces = 2; pieces <= 8; ++pieces) {
    const ObjTriangles split = parseObjTriangles(relative, kMtl, {}, "test", pieces);
    EXPECT_EQ(split.pieces, 1u) << pieces;
    expectSame(split, whole, std::to_string(pieces) + " pieces");
  }
  LoadLimits limits;
  limits.maxTriangles = 15;
  const auto error = [&](const std::string& text, std::size_t pieces) {
    try {
      parseObjTriangles(text, kMtl, limits, "test", pieces);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(read without error)");
  };
  const std::string missing =
      std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3\nf 1 2 3\nf 1 2 4\nf 1 2 3\n");
  for (std::size_t pieces = 2; pieces <= 8; ++pieces) {
    EXPECT_EQ(error(kPieceText, pieces), "test has more triangles than the limit of 15") << pieces;
    EXPECT_EQ(error(missing, pieces), error(missing, 1)) << pieces;
  }
  EXPECT_NE(error(missing, 1).find("test face 4 refers to a vertex"), std::string::npos)
      << error(missing, 1);
}

// A real asset whose texture is a JPEG (Debian's assimp-testmodels: the
// spider's map_Kd files): each material gets its image, decoded.
TEST(ObjLoad, TheSpidersJpegTexturesAreRead) {
  const std::filesystem::path folder = "/usr/share/assimp/models/OBJ";
  if (!std::filesystem::exists(folder / "spider.obj")) GTEST_SKIP() << "assimp-testmodels is not installed";
  DirectorySource files(folder, std::size_t{64} << 20);
  SceneBudget budget;
  const MeshModel spider = loadObj(files, "spider.obj", "spider", budget, true);
  EXPECT_TRUE(spider.warnings.empty()) << spider.warnings.front();
  ASSERT_FALSE(spider.textures.empty());
  for (const Texture& t : spider.textures) {
    ASSERT_TRUE(t.image);
    EXPECT_GT(t.image->width, 16);
    EXPECT_EQ(t.image->rgb.size(), static_cast<std::size_t>(t.image->width) * t.image->height * 3);
    std::size_t dark = 0;  // a decoded photograph, not a blank buffer
    for (const std::uint8_t v : t.image->rgb) dark += v < 8 ? 1 : 0;
    EXPECT_LT(dark, t.image->rgb.size() / 2);
  }
}

// `v x y z r g b`: colours when the first vertex line has them, each v line's
// in order (white for one without), none otherwise; any spacing, CRLF.
TEST(ObjLoad, VertexColorsAfterThePosition) {
  EXPECT_EQ(objVertexColors("# c\n  v 0 0 0 1 0.5 0.25\r\nvn 0 0 1\nv\t1 0 0 0 1 0\nv 0 1 0\nvt 0 0\n"),
            (std::vector<float>{1, 0.5f, 0.25f, 0, 1, 0, 1, 1, 1}));
  EXPECT_TRUE(objVertexColors("v 0 0 0\nv 1 0 0 1 0 0\n").empty());
  EXPECT_TRUE(objVertexColors("v 0 0 0 1\nvn 1 2 3\n").empty());
  EXPECT_TRUE(objVertexColors("").empty());
  // A mesh gets each corner's position's colour, through the callback
  // reader (triangles) and through LoadObj (a pentagon) alike.
  for (const char* face : {"f 1 2 3\nf 1 3 4\n", "f 1 2 3 4 5\n"}) {
    const MeshModel m = load(std::string("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0 1 1 1\n") +
                             "v -0.5 0.5 0 0.5 0.5 0.5\n" + face);
    ASSERT_EQ(m.meshes.size(), 1u);
    const MeshInput& mesh = m.meshes[0];
    ASSERT_EQ(mesh.colors.size(), mesh.positions.size()) << face;
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const glm::vec3 p = mesh.positions[v], c = mesh.colors[v];
      const glm::vec3 expected = p == glm::vec3(0, 0, 0)   ? glm::vec3(1, 0, 0)
                                 : p == glm::vec3(1, 0, 0) ? glm::vec3(0, 1, 0)
                                 : p == glm::vec3(1, 1, 0) ? glm::vec3(0, 0, 1)
                                 : p == glm::vec3(0, 1, 0) ? glm::vec3(1, 1, 1)
                                                           : glm::vec3(0.5f);
      EXPECT_EQ(c, expected) << face << " vertex " << v;
    }
  }
  EXPECT_TRUE(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").meshes[0].colors.empty());
}

}  // namespace
}  // namespace glint
