#include "common/geometry/region_query.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>

namespace glint {
namespace {

// The plane's signed distance to the box's corner that lies farthest inside.
float nearestCornerDistance(const glm::vec4& plane, const Bounds3& box) {
  const glm::vec3 corner(plane.x >= 0.0f ? box.min.x : box.max.x,
                         plane.y >= 0.0f ? box.min.y : box.max.y,
                         plane.z >= 0.0f ? box.min.z : box.max.z);
  return glm::dot(glm::vec3(plane), corner) - plane.w;
}

bool boxSeparated(const Bounds3& box, const ConvexRegion& region) {
  const float s = region.slack;
  for (int axis = 0; axis < 3; ++axis) {
    if (box.min[axis] > region.box.max[axis] + s || box.max[axis] < region.box.min[axis] - s)
      return true;
  }
  for (const glm::vec4& plane : region.planes) {
    if (nearestCornerDistance(plane, box) > s) return true;
  }
  return false;
}

bool isShared(const glm::vec3& v, const ConvexRegion& region) {
  return std::find(region.shared.begin(), region.shared.end(), v) != region.shared.end();
}

// Whether vertex v lies beyond the plane, or is a shared corner on it, or
// lies in the open base.
bool outside(const glm::vec3& v, std::size_t plane, const ConvexRegion& region) {
  const glm::vec4& p = region.planes[plane];
  const float distance = glm::dot(glm::vec3(p), v) - p.w;
  if (distance > region.slack) return true;
  if (plane == 0 && region.openBase && distance >= -0.1f * region.slack) return true;
  return std::abs(distance) <= region.slack && isShared(v, region);
}

bool triangleSeparated(const std::array<glm::vec3, 3>& v, const glm::vec3& normal,
                       const ConvexRegion& region) {
  const float s = region.slack;
  for (std::size_t plane = 0; plane < region.planes.size(); ++plane) {
    if (outside(v[0], plane, region) && outside(v[1], plane, region) &&
        outside(v[2], plane, region))
      return true;
  }
  // The triangle's plane separates when every corner lies strictly on one
  // side, but for shared corners lying in it: the region then meets the
  // plane in those corners alone.
  int above = 0, below = 0, touching = 0;
  for (const glm::vec3& c : region.corners) {
    const float distance = glm::dot(normal, c - v[0]);
    above += distance > s ? 1 : 0;
    below += distance < -s ? 1 : 0;
    touching += std::abs(distance) <= s && isShared(c, region) ? 1 : 0;
  }
  const int all = static_cast<int>(region.corners.size()) - touching;
  return all > 0 && (above == all || below == all);
}

bool sphereSeparated(const Sphere& sphere, const ConvexRegion& region) {
  for (const glm::vec4& plane : region.planes) {
    if (glm::dot(glm::vec3(plane), sphere.centre) - plane.w > sphere.radius + region.slack)
      return true;
  }
  return false;
}

bool primitiveSeparated(const Geometry& geometry, std::uint32_t prim, const ConvexRegion& region) {
  if (geometry.isSphere(prim)) {
    return sphereSeparated(geometry.spheres()[prim - geometry.triangles().size()], region);
  }
  const Triangle& t = geometry.triangles()[prim];
  const auto& p = geometry.positions();
  return triangleSeparated({p[t.v[0]], p[t.v[1]], p[t.v[2]]}, geometry.faceNormals()[prim], region);
}

}  // namespace

bool primitiveInRegion(const Geometry& geometry, std::uint32_t prim, const ConvexRegion& region) {
  return !primitiveSeparated(geometry, prim, region);
}

glm::vec4 planeThrough(const glm::vec3& point, glm::vec3 n, const glm::vec3& inside) {
  n = glm::normalize(n);
  if (glm::dot(n, inside - point) > 0.0f) n = -n;
  return {n, glm::dot(n, point)};
}

void finishRegion(ConvexRegion& region) {
  float largest = 0.0f;
  for (const glm::vec3& c : region.corners) {
    region.box.expand(c);
    largest = std::max({largest, std::abs(c.x), std::abs(c.y), std::abs(c.z)});
  }
  region.slack = largest * 1e-5f;
}

std::vector<std::uint32_t> primitivesInRegion(const Bvh& bvh, const Geometry& geometry,
                                              const ConvexRegion& region, std::uint32_t skip) {
  std::vector<std::uint32_t> found;
  const std::vector<BvhNode>& nodes = bvh.nodes();
  if (nodes.empty()) return found;
  std::vector<std::uint32_t> stack{0};
  const auto visit = [&](std::uint32_t prim) {
    if (prim != skip && !primitiveSeparated(geometry, prim, region)) found.push_back(prim);
  };
  while (!stack.empty()) {
    const BvhNode& node = nodes[stack.back()];
    stack.pop_back();
    for (int lane = 0; lane < node.children; ++lane) {
      if (boxSeparated(node.boxes.get(lane), region)) continue;
      const std::uint16_t count = node.count[lane];
      if (count == 0) {
        stack.push_back(node.offset[lane]);
      } else if (count & kBlockLeaf) {
        const TriangleBlock& block = bvh.blocks()[node.offset[lane]];
        for (int i = 0; i < (count & ~kBlockLeaf); ++i) {
          visit(block.prims[static_cast<std::size_t>(i)]);
        }
      } else {
        for (std::uint32_t i = 0; i < count; ++i) {
          visit(bvh.primIds()[node.offset[lane] + i]);
        }
      }
    }
  }
  return found;
}

}  // namespace glint
