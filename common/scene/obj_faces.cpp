#include "common/scene/obj_faces.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstring>
#include <istream>
#include <map>
#include <memory>
#include <streambuf>
#include <utility>

#include "common/base/compute_pool.h"
#include "common/base/error.h"
#include "common/base/heap_tuning.h"
#include "common/scene/obj_colors.h"

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
  TextBuffer(const char* begin, const char* end) {
    char* first = const_cast<char*>(begin);  // only ever read
    setg(first, first, first + (end - begin));
  }
};

// tinyobjloader's LoadObj would split a polygon of more than four corners by
// ear clipping, which its callback interface does not offer.
struct NeedsEarClipping {};

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
      throw InputError(where_ + " has more triangles than the limit of " +
                       std::to_string(limits_.maxTriangles));
    }
    for (int k = 0; k < count; ++k) corners_.push_back(corners[k]);  // (a range insert costs a call a face)
    sizes_.push_back(static_cast<std::uint8_t>(count));
    materials_.push_back(material);
  }

  std::size_t triangles() const { return triangles_; }

  // Room for `faces` more faces with `corners` corners in all.
  void reserve(std::size_t faces, std::size_t corners) {
    reservePrefaulted(corners_, corners_.size() + corners);
    reservePrefaulted(sizes_, sizes_.size() + faces);
    reservePrefaulted(materials_, materials_.size() + faces);
  }
  std::size_t faces() const { return sizes_.size(); }
  std::size_t corners() const { return corners_.size(); }

  // Appends the faces of a later piece of the text, each material code
  // passed through remap.
  template <typename Remap>
  void append(const FaceList& later, Remap remap) {
    corners_.insert(corners_.end(), later.corners_.begin(), later.corners_.end());
    sizes_.insert(sizes_.end(), later.sizes_.begin(), later.sizes_.end());
    for (const int code : later.materials_) materials_.push_back(remap(code));
    triangles_ += later.triangles_;
  }

  // The faces as triangles over `out.attrib` (filled by the caller), into
  // `out`: each face's corners checked, quads split. Uses the list up.
  void triangulate(ObjTriangles& out);

 private:
  void checkFace(std::size_t face, const index_t* corners, int count,
                 const tinyobj::attrib_t& attrib) const;

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

void FaceList::checkFace(std::size_t face, const index_t* corners, int count,
                         const tinyobj::attrib_t& attrib) const {
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
  const auto at = [&](const index_t& c, std::size_t axis) {
    return v[3 * static_cast<std::size_t>(c.vertex_index) + axis];
  };
  const real_t e02x = at(q[2], 0) - at(q[0], 0), e02y = at(q[2], 1) - at(q[0], 1),
               e02z = at(q[2], 2) - at(q[0], 2);
  const real_t e13x = at(q[3], 0) - at(q[1], 0), e13y = at(q[3], 1) - at(q[1], 1),
               e13z = at(q[3], 2) - at(q[1], 2);
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
  return back <= static_cast<long long>(readSoFar)
             ? static_cast<int>(static_cast<long long>(readSoFar) - back)
             : kNowhere;
}

// The first word of a usemtl line's rest, as LoadObj takes the name.
std::string firstWord(const char* text) {
  const std::string rest(text);
  const std::size_t start = rest.find_first_not_of(" \t");
  if (start == std::string::npos) return "";
  return rest.substr(start, rest.find_first_of(" \t\r", start) - start);
}

// The MTL's materials, read once by tinyobjloader's LoadMtl, and its map
// from a name to the first material of that name.
struct MaterialTable {
  std::vector<tinyobj::material_t> materials;
  std::map<std::string, int> ids;

  explicit MaterialTable(const std::string& text) {
    if (text.empty()) return;
    TextBuffer buffer(text.data(), text.data() + text.size());
    std::istream stream(&buffer);
    std::string warnings, errors;
    tinyobj::LoadMtl(&ids, &materials, &stream, &warnings, &errors);
  }
  int find(const std::string& name) const {
    const auto it = ids.find(name);
    return it == ids.end() ? -1 : it->second;
  }
};

// Hands the table to LoadObjWithCallback at an mtllib line: it calls the
// mtllib callback only when the library holds a material.
class MaterialHandover : public tinyobj::MaterialReader {
 public:
  explicit MaterialHandover(const MaterialTable& table) : table_(table) {}
  bool operator()(const std::string& /*name*/, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* /*ids*/, std::string* /*warn*/,
                  std::string* /*err*/) override {
    materials->insert(materials->end(), table_.materials.begin(), table_.materials.end());
    return !table_.materials.empty();
  }

 private:
  const MaterialTable& table_;
};

// A face's material before the pieces are joined, in a piece after the
// first: kInherited, the one in use where the piece starts; kPendingFirst
// - i, the name of the piece's i-th usemtl line, read before any mtllib
// line of the piece (whether the name counts depends on the pieces before).
constexpr int kInherited = -2;
constexpr int kPendingFirst = -3;

// What the callbacks of LoadObjWithCallback fill for one piece of the text
// (the whole of it, or a part that starts after a line): its attributes,
// its faces (indices resolved as the line is read, as LoadObj does), each
// face's material, found by name once an mtllib line has been read.
struct PieceReader {
  PieceReader(const MaterialTable& table, bool first, const LoadLimits& limits,
              const std::string& where)
      : table(table),
        first(first),
        faces(limits, where, "face"),
        material(first ? -1 : kInherited) {}

  const MaterialTable& table;
  const bool first;  // the piece the text starts with
  tinyobj::attrib_t attrib;
  FaceList faces;
  int material;
  bool sawMtllib = false;
  bool relative = false;  // a later piece met a relative index: only a whole read resolves it
  std::vector<std::string> pending;
  std::vector<index_t> face;

  static PieceReader& of(void* user) { return *static_cast<PieceReader*>(user); }

  static void vertex(void* user, real_t x, real_t y, real_t z, real_t /*w*/) {
    std::vector<real_t>& v = of(user).attrib.vertices;
    of(user).faces.checkVertices(v.size() / 3 + 1);
    v.insert(v.end(), {x, y, z});
  }
  static void normal(void* user, real_t x, real_t y, real_t z) {
    of(user).attrib.normals.insert(of(user).attrib.normals.end(), {x, y, z});
  }
  static void texcoord(void* user, real_t u, real_t v, real_t /*w*/) {
    of(user).attrib.texcoords.insert(of(user).attrib.texcoords.end(), {u, v});
  }
  static void indices(void* user, index_t* raw, int count) {
    PieceReader& r = of(user);
    if (count < 3) return;  // LoadObj drops such faces too
    if (count > 4) throw NeedsEarClipping{};
    const tinyobj::attrib_t& a = r.attrib;
    r.face.resize(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) {
      const bool relative =
          raw[k].vertex_index < 0 || raw[k].normal_index < 0 || raw[k].texcoord_index < 0;
      r.relative = r.relative || (relative && !r.first);
      r.face[k] = {resolveIndex(raw[k].vertex_index, a.vertices.size() / 3, kNowhere),
                   resolveIndex(raw[k].normal_index, a.normals.size() / 3, -1),
                   resolveIndex(raw[k].texcoord_index, a.texcoords.size() / 2, -1)};
    }
    r.faces.add(r.face.data(), count, r.material);
  }
  static void usemtl(void* user, const char* name, int /*id as the callback parser found it*/) {
    PieceReader& r = of(user);
    if (r.sawMtllib || r.first) {
      r.material = r.sawMtllib ? r.table.find(firstWord(name)) : -1;
      return;
    }
    r.pending.push_back(firstWord(name));
    r.material = kPendingFirst - static_cast<int>(r.pending.size() - 1);
  }
  static void mtllib(void* user, const tinyobj::material_t* /*materials*/, int /*count*/) {
    of(user).sawMtllib = true;
  }

  // Room for the attributes and faces of text [begin, end), counted from
  // the first letters of its lines: growing the arrays as the lines come
  // copied them and faulted their pages in one by one (heap_tuning.h).
  void reserveFor(const char* begin, const char* end) {
    std::size_t counts[4] = {0, 0, 0, 0};  // v, vn, vt, f lines
    for (const char* line = begin; line < end;) {
      while (line < end && (*line == ' ' || *line == '\t')) ++line;
      if (end - line >= 2) {
        const bool vertexLine = line[0] == 'v';
        counts[0] += vertexLine && (line[1] == ' ' || line[1] == '\t') ? 1 : 0;
        counts[1] += vertexLine && line[1] == 'n' ? 1 : 0;
        counts[2] += vertexLine && line[1] == 't' ? 1 : 0;
        counts[3] += line[0] == 'f' && (line[1] == ' ' || line[1] == '\t') ? 1 : 0;
      }
      const void* next = std::memchr(line, '\n', static_cast<std::size_t>(end - line));
      line = next ? static_cast<const char*>(next) + 1 : end;
    }
    reservePrefaulted(attrib.vertices, 3 * counts[0]);
    reservePrefaulted(attrib.normals, 3 * counts[1]);
    reservePrefaulted(attrib.texcoords, 2 * counts[2]);
    faces.reserve(counts[3], 3 * counts[3]);  // triangles, at first guess
  }

  // Reads text [begin, end); NeedsEarClipping and InputError pass through.
  void read(const char* begin, const char* end) {
    reserveFor(begin, end);
    tinyobj::callback_t callbacks;
    callbacks.vertex_cb = &vertex;
    callbacks.normal_cb = &normal;
    callbacks.texcoord_cb = &texcoord;
    callbacks.index_cb = &indices;
    callbacks.usemtl_cb = &usemtl;
    callbacks.mtllib_cb = &mtllib;
    TextBuffer buffer(begin, end);
    std::istream stream(&buffer);
    MaterialHandover handover(table);
    tinyobj::LoadObjWithCallback(stream, callbacks, this, &handover);
  }
};

// The least a piece read at once is long: a text under twice this is read
// whole, as thread start-up would cost more than the piece saves.
constexpr std::size_t kPieceBytes = std::size_t{4} << 20;

std::size_t piecesFor(std::size_t bytes) {
  const auto threads = static_cast<std::size_t>(computePool().size());
  return std::max<std::size_t>(1, std::min(threads, bytes / kPieceBytes));
}

// Where the text is cut into (up to) `pieces` parts: after the line in
// which each k / pieces of it falls. Piece i is [cuts[i], cuts[i + 1]).
std::vector<const char*> cutsOf(const std::string& text, std::size_t pieces) {
  std::vector<const char*> cuts{text.data()};
  for (std::size_t k = 1; k < pieces; ++k) {
    const std::size_t from =
        std::max(text.size() * k / pieces, static_cast<std::size_t>(cuts.back() - text.data()));
    const std::size_t line = text.find('\n', from);
    if (line == std::string::npos) break;
    cuts.push_back(text.data() + line + 1);
  }
  cuts.push_back(text.data() + text.size());
  return cuts;
}

// The later pieces joined onto the first (a whole read is one piece), into
// `out`: attributes and faces in file order, each later face's material
// code made what a whole read gives.
void joinPieces(std::vector<std::unique_ptr<PieceReader>>& readers, const MaterialTable& table,
                ObjTriangles& out) {
  PieceReader& whole = *readers[0];
  std::size_t faces = 0, corners = 0, sizes[3] = {0, 0, 0};
  for (std::size_t i = 1; i < readers.size(); ++i) {
    faces += readers[i]->faces.faces();
    corners += readers[i]->faces.corners();
    sizes[0] += readers[i]->attrib.vertices.size();
    sizes[1] += readers[i]->attrib.normals.size();
    sizes[2] += readers[i]->attrib.texcoords.size();
  }
  whole.faces.reserve(faces, corners);
  reservePrefaulted(whole.attrib.vertices, whole.attrib.vertices.size() + sizes[0]);
  reservePrefaulted(whole.attrib.normals, whole.attrib.normals.size() + sizes[1]);
  reservePrefaulted(whole.attrib.texcoords, whole.attrib.texcoords.size() + sizes[2]);
  bool named = whole.sawMtllib;  // usemtl names count from the first mtllib line on
  int current = whole.material;
  for (std::size_t i = 1; i < readers.size(); ++i) {
    const PieceReader& piece = *readers[i];
    const auto remap = [&](int code) {
      if (code == kInherited) return current;
      if (code <= kPendingFirst)
        return named ? table.find(piece.pending[static_cast<std::size_t>(kPendingFirst - code)])
                     : -1;
      return code;
    };
    whole.faces.append(piece.faces, remap);
    current = remap(piece.material);
    named = named || piece.sawMtllib;
    for (auto [to, from] : {std::pair{&whole.attrib.vertices, &piece.attrib.vertices},
                            std::pair{&whole.attrib.normals, &piece.attrib.normals},
                            std::pair{&whole.attrib.texcoords, &piece.attrib.texcoords}}) {
      to->insert(to->end(), from->begin(), from->end());
    }
  }
  out.attrib = std::move(whole.attrib);
  if (named) out.materials = table.materials;
  whole.faces.triangulate(out);
}

// The whole text through the callbacks, into `out`; false when the file has
// a larger polygon.
bool readWhole(const std::string& text, const MaterialTable& table, const LoadLimits& limits,
               const std::string& where, ObjTriangles& out) {
  std::vector<std::unique_ptr<PieceReader>> whole;
  whole.push_back(std::make_unique<PieceReader>(table, true, limits, where));
  try {
    whole[0]->read(text.data(), text.data() + text.size());
  } catch (const NeedsEarClipping&) {
    return false;
  }
  joinPieces(whole, table, out);
  return true;
}

// The pieces read at once on the compute pool, and joined; false where only a
// whole read gives LoadObj's answer: a piece failed (an error, a larger
// polygon: the whole read meets it in file order), a later piece used a
// relative index, or the pieces together pass a limit.
bool readPieces(const std::string& text, const MaterialTable& table, const LoadLimits& limits,
                const std::string& where, std::size_t pieces, ObjTriangles& out) {
  const std::vector<const char*> cuts = cutsOf(text, pieces);
  std::vector<std::unique_ptr<PieceReader>> readers;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    readers.push_back(std::make_unique<PieceReader>(table, i == 0, limits, where));
  std::vector<char> failed(readers.size(), 0);
  const auto readOne = [&](std::size_t i) {
    try {
      readers[i]->read(cuts[i], cuts[i + 1]);
    } catch (...) {
      failed[i] = 1;
    }
  };
  computePool().parallelFor(readers.size(), readOne);
  std::size_t vertices = 0, triangles = 0;
  for (std::size_t i = 0; i < readers.size(); ++i) {
    if (failed[i] || readers[i]->relative) return false;
    vertices += readers[i]->attrib.vertices.size() / 3;
    triangles += readers[i]->faces.triangles();
  }
  if (vertices > limits.maxVertices || triangles > limits.maxTriangles) return false;
  joinPieces(readers, table, out);
  out.pieces = readers.size();
  return true;
}

// Any polygon, through LoadObj and its triangulation.
void readByLoadObj(const std::string& text, const std::string& mtlText, const std::string& where,
                   FaceList& faces, ObjTriangles& out) {
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
        throw InputError(where + " face " + std::to_string(f) + " of '" + shape.name +
                         "' could not be triangulated");
      }
      faces.add(&mesh.indices[3 * f], 3, f < mesh.material_ids.size() ? mesh.material_ids[f] : -1);
    }
  }
}

// The text's triangles and attributes (its colours aside).
ObjTriangles parseFaces(const std::string& text, const std::string& mtlText, const LoadLimits& limits,
                        const std::string& where, std::size_t pieces) {
  const MaterialTable table(mtlText);
  ObjTriangles out;
  if (pieces == 0) pieces = piecesFor(text.size());
  if (pieces > 1 && readPieces(text, table, limits, where, pieces, out)) return out;
  if (readWhole(text, table, limits, where, out)) return out;
  ObjTriangles polygons;
  FaceList triangles(limits, where, "triangle");
  readByLoadObj(text, mtlText, where, triangles, polygons);
  triangles.triangulate(polygons);
  return polygons;
}

}  // namespace

ObjTriangles parseObjTriangles(const std::string& text, const std::string& mtlText,
                               const LoadLimits& limits, const std::string& where,
                               std::size_t pieces) {
  ObjTriangles out = parseFaces(text, mtlText, limits, where, pieces);
  out.attrib.colors = objVertexColors(text);  // LoadObj's own (white where absent) replaced
  return out;
}

}  // namespace glint
