#include "common/scene/scene_budget.h"

#include <cstdio>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/geometry/bvh.h"
#include "common/geometry/bvh_collapse.h"
#include "common/geometry/bvh_lanes.h"
#include "common/geometry/bvh_split.h"
#include "common/base/error.h"
#include "common/geometry/geometry.h"

namespace glint {
namespace {

std::string mib(std::size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / 1048576.0);
  return text;
}

}  // namespace

// A vertex: position, normal, texture coordinate; a triangle: its indices and
// face normal (Geometry::addMesh).
const std::size_t SceneBudget::kBytesPerVertex = 2 * sizeof(glm::vec3) + sizeof(glm::vec2);
const std::size_t SceneBudget::kBytesPerTriangle = sizeof(Triangle) + sizeof(glm::vec3);
const std::size_t SceneBudget::kBytesPerSphere = sizeof(Sphere);
// The BVH: at most one 8-wide node, one index and half a triangle block (a
// block holds two triangles or more) per primitive once built, and while it
// is built a BuildPrimitive, up to two binary nodes and the collapse's
// choice for each, and half a block's range.
const std::size_t SceneBudget::kBvhBytesPerPrimitive =
    sizeof(BvhNode) + sizeof(std::uint32_t) + sizeof(TriangleBlock) / 2 + sizeof(BuildPrimitive) +
    2 * (sizeof(BinaryNode) + sizeof(BvhLanePlan::Choice)) + sizeof(BlockRange) / 2;

SceneBudget::SceneBudget(const LoadLimits& limits, std::string limitName, MemoryGauge* shared)
    : limits_(limits), limitName_(std::move(limitName)), shared_(shared) {}

SceneBudget::~SceneBudget() {
  if (shared_) shared_->give(used_);
}

void SceneBudget::charge(std::size_t bytes, const std::string& place, const char* when) {
  checkTime(place);
  const std::size_t total = used_ + bytes;
  if (bytes > limits_.maxSceneBytes || total > limits_.maxSceneBytes) {
    throw InputError(place + ": the scene would hold " + mib(total) + " " + when + ", " +
                     mib(total - limits_.maxSceneBytes) + " over " + limitName_ + " of " +
                     mib(limits_.maxSceneBytes));
  }
  if (shared_ && !shared_->take(bytes)) {
    throw BusyError(place + ": the scene's " + mib(total) + " do not fit beside the scenes being built now (" +
                     mib(shared_->used()) + " of " + mib(shared_->capacity()) + ", " + shared_->name() +
                     "); try again later");
  }
  used_ = total;
}

void SceneBudget::chargeImage(int width, int height, const std::string& place, std::size_t bytesPerTexel) {
  charge(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * bytesPerTexel, place);
}

void SceneBudget::chargeMesh(std::size_t vertices, std::size_t triangles, const std::string& place) {
  charge(vertices * kBytesPerVertex + triangles * (kBytesPerTriangle + kBvhBytesPerPrimitive), place);
}

std::size_t SceneBudget::chargeJson(std::size_t values, std::size_t members, const std::string& place) {
  const std::size_t bytes = values * kJsonBytesPerValue + members * kJsonBytesPerMember;
  const std::size_t share = limits_.maxSceneBytes / kJsonShare;
  if (bytes > share) {
    throw InputError(place + ": parsing it would take " + mib(bytes) + ", over the " + mib(share) +
                     " (a quarter of " + limitName_ + ") that a scene's JSON may take; put large meshes in "
                     "files (.ply, .obj, .gltf)");
  }
  charge(bytes, place);
  return bytes;
}

void SceneBudget::refund(std::size_t bytes) {
  used_ -= bytes;
  if (shared_) shared_->give(bytes);
}

void SceneBudget::chargeSphere(const std::string& place) { charge(kBytesPerSphere + kBvhBytesPerPrimitive, place); }

}  // namespace glint
