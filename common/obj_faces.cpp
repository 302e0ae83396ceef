#include "common/obj_faces.h"

#include <climits>
#include <cstdint>
#include <istream>
#include <map>
#include <streambuf>

#include "common/error.h"

namespace glint {
namespace {

using tinyobj::index_t;
using tinyobj::real_t;

// An index that names nothing the file has: every range check fails on it.
constexpr int kNowhere = INT_MAX;

// A read-only stream over text already in memory (LoadObjWithCallback
// reads a std::istream; a std::istringstream would copy the text first).
class TextBuffer : public std::streambuf {
 public:
  explicit TextBuffer(const std::string& text) {
    char* begin = const_cast<char*>(text.data());  // only ever read
    setg(begin, begin, begin + text.size());
  }
};

// tinyobjloader's LoadObj would split a polygon of more than four corners by
// ear clipping, which its callback interface does not offer.
struct NeedsEarClipping {};

// The mtllib's materials for LoadObjWithCallback, which tells the callbacks
// about a library only when it holds a material.
class MaterialText : public tinyobj::MaterialReader {
 public:
  explicit MaterialText(const std::string& text) : buffer_(text), stream_(&buffer_), reader_(stream_) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* ids, std::string* warn, std::string* err) override {
    return reader_(name, materials, ids, warn, err) && !materials->empty();
  }

 private:
  TextBuffer buffer_;
  std::istream stream_;
  tinyobj::MaterialStreamReader reader_;
};

// The faces as read: corners (zero-based), corners per face (3 or 4) and a
// material per face, with the limits checked as they arrive. An error names
// a face by its place in the file, counted from 1 in `unit`s: "face" (as
// the file has them), "triangle" (as LoadObj split them).
class FaceList {
 public:
  FaceList(const LoadLimits& limits, const std::string& where, const char* unit)
      : limits_(limits), where_(where), unit_(unit) {}

  void checkVertices(std::size_t count) const {
    if (count > limits_.maxVertices) {
      throw InputError(where_ + " has " + std::to_string(count) + " vertices, over the limit of " +
                       std::to_string(limits_.maxVertices));
    }
  }
  void add(const index_t* corners, int count, int material) {
    triangles_ += static_cast<std::size_t>(count - 2);
    if (triangles_ > limits_.maxTriangles) {
      throw InputError(where_ + " has more triangles than the limit of " + std::to_string(limits_.maxTriangles));
    }
    corners_.insert(corners_.end(), corners, corners + count);
    sizes_.push_back(static_cast<std::uint8_t>(count));
    materials_.push_back(material);
  }

  // The faces as triangles over `out.attrib` (filled by the caller), into
  // `out`: each face's corners checked, quads split. Uses the list up.
  void triangulate(ObjTriangles& out);

 private:
  void checkFace(std::size_t face, const index_t* corners, int count, const tinyobj::attrib_t& attrib) const;

  const LoadLimits& limits_;
  const std::string& where_;
  const char* unit_;
  std::size_t triangles_ = 0;
  std::vector<index_t> corners_;
  std::vector<std::uint8_t> sizes_;
  std::vector<int> materials_;
};

bool within(int index, std::size_t count, int lowest) {
  return index >= lowest && (index < 0 || static_cast<std::size_t>(index) < count);
}

void FaceList::checkFace(std::size_t face, const index_t* corners, int count, const tinyobj::attrib_t& attrib) const {
  for (int k = 0; k < count; ++k) {
    const index_t& c = corners[k];
    if (!within(c.vertex_index, attrib.vertices.size() / 3, 0) ||
        !within(c.normal_index, attrib.normals.size() / 3, -1) ||
        !within(c.texcoord_index, attrib.texcoords.size() / 2, -1)) {
      throw InputError(where_ + " " + unit_ + " " + std::to_string(face + 1) +
                       " refers to a vertex, normal or uv that the file does not have (it has " +
                       std::to_string(attrib.vertices.size() / 3) + " vertices, " +
                       std::to_string(attrib.normals.size() / 3) + " normals, " +
                       std::to_string(attrib.texcoords.size() / 2) + " uvs)");
    }
  }
}

// tinyobjloader's LoadObj splits a quad along its shorter diagonal: 0-2 into
// [0,1,2] [0,2,3], else 1-3 into [0,1,3] [1,2,3]; the same float operations
// here give the same split.
bool splitsAlong02(const index_t* q, const std::vector<real_t>& v) {
  const auto at = [&](const index_t& c, std::size_t axis) { return v[3 * static_cast<std::size_t>(c.vertex_index) + axis]; };
  const real_t e02x = at(q[2], 0) - at(q[0], 0), e02y = at(q[2], 1) - at(q[0], 1), e02z = at(q[2], 2) - at(q[0], 2);
  const real_t e13x = at(q[3], 0) - at(q[1], 0), e13y = at(q[3], 1) - at(q[1], 1), e13z = at(q[3], 2) - at(q[1], 2);
  const real_t sqr02 = e02x * e02x + e02y * e02y + e02z * e02z;
  const real_t sqr13 = e13x * e13x + e13y * e13y + e13z * e13z;
  return sqr02 < sqr13;
}

void FaceList::triangulate(ObjTriangles& out) {
  for (std::size_t f = 0, first = 0; f < sizes_.size(); first += sizes_[f], ++f) {
    checkFace(f, corners_.data() + first, sizes_[f], out.attrib);
  }
  if (triangles_ == sizes_.size()) {  // no quad: the faces are the triangles
    out.corners = std::move(corners_);
    out.materialOf = std::move(materials_);
    return;
  }
  out.corners.reserve(3 * triangles_);
  out.materialOf.reserve(triangles_);
  for (std::size_t f = 0, first = 0; f < sizes_.size(); first += sizes_[f], ++f) {
    const index_t* c = corners_.data() + first;
    if (sizes_[f] == 3) {
      out.corners.insert(out.corners.end(), c, c + 3);
    } else if (splitsAlong02(c, out.attrib.vertices)) {
      out.corners.insert(out.corners.end(), {c[0], c[1], c[2], c[0], c[2], c[3]});
    } else {
      out.corners.insert(out.corners.end(), {c[0], c[1], c[3], c[1], c[2], c[3]});
    }
    out.materialOf.insert(out.materialOf.end(), sizes_[f] - 2u, materials_[f]);
  }
}

// tinyobjloader's index rule (its fixIndex): one-based; a negative index
// counts back from the last element read so far; 0 is no index (a missing
// normal or uv; for a vertex, nothing).
int resolveIndex(int raw, std::size_t readSoFar, int absent) {
  if (raw > 0) return raw - 1;
  if (raw == 0) return absent;
  const long long back = -static_cast<long long>(raw);
  return back <= static_cast<long long>(readSoFar) ? static_cast<int>(static_cast<long long>(readSoFar) - back)
                                                   : kNowhere;
}

// The first word of a usemtl line's rest, as LoadObj takes the name.
std::string firstWord(const char* text) {
  const std::string rest(text);
  const std::size_t start = rest.find_first_not_of(" \t");
  if (start == std::string::npos) return "";
  return rest.substr(start, rest.find_first_of(" \t\r", start) - start);
}

// What the callbacks of LoadObjWithCallback fill: the attributes, the faces
// (their indices resolved as the line is read, as LoadObj does), and each
// face's material, found by name once the mtllib line has been read.
struct CallbackReader {
  ObjTriangles& out;
  FaceList& faces;
  std::map<std::string, int> materialIds;  // the first material of a name, as LoadObj's map
  int material = -1;
  std::vector<index_t> face;

  static CallbackReader& of(void* user) { return *static_cast<CallbackReader*>(user); }

  static void vertex(void* user, real_t x, real_t y, real_t z, real_t /*w*/) {
    std::vector<real_t>& v = of(user).out.attrib.vertices;
    of(user).faces.checkVertices(v.size() / 3 + 1);
    v.insert(v.end(), {x, y, z});
  }
  static void normal(void* user, real_t x, real_t y, real_t z) {
    of(user).out.attrib.normals.insert(of(user).out.attrib.normals.end(), {x, y, z});
  }
  static void texcoord(void* user, real_t u, real_t v, real_t /*w*/) {
    of(user).out.attrib.texcoords.insert(of(user).out.attrib.texcoords.end(), {u, v});
  }
  static void indices(void* user, index_t* raw, int count) {
    CallbackReader& r = of(user);
    if (count < 3) return;  // LoadObj drops such faces too
    if (count > 4) throw NeedsEarClipping{};
    const tinyobj::attrib_t& a = r.out.attrib;
    r.face.resize(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) {
      r.face[k] = {resolveIndex(raw[k].vertex_index, a.vertices.size() / 3, kNowhere),
                   resolveIndex(raw[k].normal_index, a.normals.size() / 3, -1),
                   resolveIndex(raw[k].texcoord_index, a.texcoords.size() / 2, -1)};
    }
    r.faces.add(r.face.data(), count, r.material);
  }
  static void usemtl(void* user, const char* name, int /*id as the callback parser found it*/) {
    CallbackReader& r = of(user);
    const auto it = r.materialIds.find(firstWord(name));
    r.material = it == r.materialIds.end() ? -1 : it->second;
  }
  static void mtllib(void* user, const tinyobj::material_t* materials, int count) {
    CallbackReader& r = of(user);
    r.out.materials.assign(materials, materials + count);
    for (int i = 0; i < count; ++i) r.materialIds.emplace(materials[i].name, i);
  }
};

// Triangles and quads through the callbacks; false when the file has a
// larger polygon.
bool readByCallbacks(const std::string& text, const std::string& mtlText, FaceList& faces, ObjTriangles& out) {
  CallbackReader reader{out, faces, {}, -1, {}};
  tinyobj::callback_t callbacks;
  callbacks.vertex_cb = &CallbackReader::vertex;
  callbacks.normal_cb = &CallbackReader::normal;
  callbacks.texcoord_cb = &CallbackReader::texcoord;
  callbacks.index_cb = &CallbackReader::indices;
  callbacks.usemtl_cb = &CallbackReader::usemtl;
  callbacks.mtllib_cb = &CallbackReader::mtllib;
  TextBuffer buffer(text);
  std::istream stream(&buffer);
  MaterialText materials(mtlText);
  try {
    tinyobj::LoadObjWithCallback(stream, callbacks, &reader, mtlText.empty() ? nullptr : &materials);
  } catch (const NeedsEarClipping&) {
    return false;
  }
  return true;
}

// Any polygon, through LoadObj and its triangulation.
void readByLoadObj(const std::string& text, const std::string& mtlText, const std::string& where, FaceList& faces,
                   ObjTriangles& out) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, mtlText, config)) {
    throw InputError(where + " is not a valid OBJ file: " + reader.Error());
  }
  faces.checkVertices(reader.GetAttrib().vertices.size() / 3);
  out.attrib = reader.GetAttrib();
  out.materials = reader.GetMaterials();
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      if (mesh.num_face_vertices[f] != 3) {
        throw InputError(where + " face " + std::to_string(f) + " of '" + shape.name + "' could not be triangulated");
      }
      faces.add(&mesh.indices[3 * f], 3, f < mesh.material_ids.size() ? mesh.material_ids[f] : -1);
    }
  }
}

}  // namespace

ObjTriangles parseObjTriangles(const std::string& text, const std::string& mtlText, const LoadLimits& limits,
                               const std::string& where) {
  ObjTriangles out;
  FaceList faces(limits, where, "face");
  if (readByCallbacks(text, mtlText, faces, out)) {
    faces.triangulate(out);
    return out;
  }
  ObjTriangles polygons;
  FaceList triangles(limits, where, "triangle");
  readByLoadObj(text, mtlText, where, triangles, polygons);
  triangles.triangulate(polygons);
  return polygons;
}

}  // namespace glint
