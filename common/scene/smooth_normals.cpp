#include "common/scene/smooth_normals.h"

#include <array>
#include <cmath>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "common/base/array_hash.h"
#include "common/math/circular.h"
#include "common/math/float_bits.h"

namespace glint {
namespace {

using Key3 = std::array<std::uint32_t, 3>;

// The key of a vector: its bits, -0 counted as +0 (adding +0 turns -0 into +0).
Key3 bitsOf(const glm::vec3& v) {
  return {floatToBits(v.x + 0.0f), floatToBits(v.y + 0.0f), floatToBits(v.z + 0.0f)};
}

using Key4 = std::array<std::uint32_t, 4>;  // a vertex and its normal's bits



// For each vertex, the point it stands at (equal positions, one point), and
// for each point the faces around it (compressed rows).
struct PointFaces {
  std::vector<std::uint32_t> pointOf;  // per vertex
  std::vector<std::uint32_t> start;    // per point, into faces; one past the last point too
  std::vector<std::uint32_t> faces;
};

PointFaces pointFaces(const MeshInput& mesh) {
  PointFaces pf;
  std::unordered_map<Key3, std::uint32_t, ArrayHash> points;
  pf.pointOf.reserve(mesh.positions.size());
  for (const glm::vec3& p : mesh.positions) {
    pf.pointOf.push_back(points.try_emplace(bitsOf(p), static_cast<std::uint32_t>(points.size())).first->second);
  }
  pf.start.assign(points.size() + 1, 0);
  for (const std::uint32_t v : mesh.indices) ++pf.start[pf.pointOf[v] + 1];
  for (std::size_t i = 1; i < pf.start.size(); ++i) pf.start[i] += pf.start[i - 1];
  pf.faces.resize(mesh.indices.size());
  std::vector<std::uint32_t> fill(pf.start.begin(), pf.start.end() - 1);
  for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
    pf.faces[fill[pf.pointOf[mesh.indices[c]]]++] = static_cast<std::uint32_t>(c / 3);
  }
  return pf;
}

}  // namespace

void smoothNormals(MeshInput& mesh, float creaseDegrees) {
  const float cosLimit = sineCosine(glm::radians(creaseDegrees)).cos;
  const std::size_t faceCount = mesh.indices.size() / 3;
  std::vector<glm::vec3> weighted(faceCount), unit(faceCount);
  for (std::size_t f = 0; f < faceCount; ++f) {
    const glm::vec3& a = mesh.positions[mesh.indices[3 * f]];
    weighted[f] = glm::cross(mesh.positions[mesh.indices[3 * f + 1]] - a, mesh.positions[mesh.indices[3 * f + 2]] - a);
    const float len = glm::length(weighted[f]);
    unit[f] = len > 0.0f ? weighted[f] / len : glm::vec3(0.0f);
  }
  const PointFaces pf = pointFaces(mesh);
  MeshInput out;
  out.material = mesh.material;
  std::unordered_map<Key4, std::uint32_t, ArrayHash> made;  // (vertex, normal) -> new vertex
  out.indices.reserve(mesh.indices.size());
  for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
    const std::uint32_t v = mesh.indices[c];
    const std::size_t f = c / 3;
    glm::vec3 sum(0.0f);
    const std::uint32_t point = pf.pointOf[v];
    for (std::uint32_t i = pf.start[point]; i < pf.start[point + 1]; ++i) {
      const std::uint32_t g = pf.faces[i];
      if (glm::dot(unit[g], unit[f]) >= cosLimit) sum += weighted[g];
    }
    const float len = glm::length(sum);
    const glm::vec3 n = len > 0.0f ? sum / len : unit[f];
    const Key3 nb = bitsOf(n);
    const auto [it, fresh] = made.try_emplace(Key4{v, nb[0], nb[1], nb[2]}, static_cast<std::uint32_t>(out.positions.size()));
    if (fresh) {
      out.positions.push_back(mesh.positions[v]);
      out.normals.push_back(n);
      if (!mesh.uvs.empty()) out.uvs.push_back(mesh.uvs[v]);
    }
    out.indices.push_back(it->second);
  }
  mesh = std::move(out);
}

}  // namespace glint
