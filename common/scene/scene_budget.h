#pragma once

#include <cstddef>
#include <string>

#include "common/base/deadline.h"
#include "common/base/memory_gauge.h"
#include "common/image/decode_budget.h"
#include "common/scene/load_limits.h"

namespace glint {

// What one scene will hold in memory once built, counted as the loader reads
// it and before each allocation that the input decides: an image's texels
// from its header (before decoding), a mesh's vertices and triangles, and the
// BVH's share of each primitive. A scene that would pass its limit (or the
// shared gauge) fails at the item that crosses it, with an InputError that
// names the place, the limit and by how much. Not thread-safe: one per load.
class SceneBudget final : public DecodeBudget {
 public:
  // Bytes each item costs (Geometry's arrays; the BVH's nodes, and what its
  // builder holds meanwhile, per primitive).
  static const std::size_t kBytesPerVertex;
  static const std::size_t kBytesPerTriangle;
  static const std::size_t kBytesPerSphere;
  static const std::size_t kBvhBytesPerPrimitive;
  // A parsed JSON document's bytes per value and per object member
  // (nlohmann::json: 31 bytes per element of a long array, 175 per object of
  // one member, measured with getrusage).
  static constexpr std::size_t kJsonBytesPerValue = 32;
  static constexpr std::size_t kJsonBytesPerMember = 128;
  // The share of the scene's limit its JSON document may take (1 / this):
  // the document describes; geometry in bulk belongs in mesh files, read
  // without a document. Keeps a parse's peak well below the scene's limit.
  static constexpr std::size_t kJsonShare = 4;

  // `limitName` says how a user changes limits.maxSceneBytes ("glintd
  // --max-scene-mb"); `shared`, if any, is drawn from too.
  explicit SceneBudget(const LoadLimits& limits = {}, std::string limitName = "the limit for one scene",
                       MemoryGauge* shared = nullptr);
  ~SceneBudget() override;
  SceneBudget(const SceneBudget&) = delete;
  SceneBudget& operator=(const SceneBudget&) = delete;

  const LoadLimits& limits() const { return limits_; }
  std::size_t maxTexturePixels() const override { return limits_.maxTexturePixels; }
  std::size_t used() const { return used_; }
  // The build's time limit, checked at every charge (before each image,
  // mesh and sphere is taken) and by checkTime(); it outlives the budget.
  void keepTo(const Deadline& deadline) { deadline_ = &deadline; }
  void checkTime(const std::string& place) const {
    if (deadline_) deadline_->check(place);
  }

  // `when` the scene would hold the bytes, in its error.
  void charge(std::size_t bytes, const std::string& place, const char* when = "once built") override;
  void chargeImage(int width, int height, const std::string& place, std::size_t bytesPerTexel) override;
  void chargeMesh(std::size_t vertices, std::size_t triangles, const std::string& place);
  void chargeSphere(const std::string& place);
  // What parsing a document of this shape takes, held until refund() (the
  // document lives while the scene is loaded from it); returns the bytes.
  std::size_t chargeJson(std::size_t values, std::size_t members, const std::string& place);
  void refund(std::size_t bytes) override;

 private:
  LoadLimits limits_;
  std::string limitName_;
  MemoryGauge* shared_;
  const Deadline* deadline_ = nullptr;
  std::size_t used_ = 0;
};

}  // namespace glint
