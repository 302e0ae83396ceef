#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "common/geometry/bvh.h"
#include "common/geometry/region_query.h"
#include "common/render/effects.h"
#include "common/render/emitter_patches.h"
#include "common/scene/scene.h"

namespace glint::gl {

// Which pixels of a raster frame see every soft light whole, proved from the
// scene's geometry: the raster shades an area or sphere light's unshadowed
// light (common/render/area_light.h, common/render/sphere_light.h), which is
// the tracer's value wherever nothing stands between the point and any point
// its shadow rays may go to. For a pixel's point p (from its depth), lifted
// off its surface towards the light by 1/1000 of its distances to the eye
// and the light, nothing may enter the pyramid from p to the light's base
// (common/geometry/region_query.h, then each primitive it finds by
// separating axes): an area light's parallelogram, or for a sphere light the
// square through its centre, square to the axis from p, that the ball's cone
// from p passes through (the ball's near side, where the rays end, lies
// within). A pixel not proved so is traced, the penumbra and the umbra
// alike. A point behind an area light's plane gets nothing from it and needs
// no proof; one within a sphere light's ball is traced.
class PenumbraProof {
 public:
  // For the soft lights the plan lets cast shadows (none: active() false).
  PenumbraProof(const Scene& scene, const EffectPlan& plan);
  bool active() const { return !lights_.empty(); }
  // The emitters' triangles too (path transport's light drawn from an
  // irradiance field): each lights both its sides, and the pyramid to it
  // stops short of it as the tracer's shadow rays do
  // (Emitters::kShortOfEmitter), so that neither it nor its neighbours in
  // its plane count as blocking.
  void addEmitters(const EmitterPatches& patches);

  // Whether every soft light reaches the whole of p's view of it.
  bool seesWhole(const glm::vec3& p, const glm::vec3& eye) const;
  // True where one ray shows that p cannot be proved to see some soft light
  // whole: a primitive meets the segment from p's lifted apex to the middle
  // of that light's base, inside the pyramid seesWhole would ask about.
  // False proves nothing. One any-hit ray a light, where a failed proof
  // walks the region query and tests each primitive it finds.
  bool plainlyBlocked(const glm::vec3& p, const glm::vec3& eye) const;
  // The same for a block of points at once: true proves it for each (nothing
  // enters the box around all their pyramids to a light); false proves
  // nothing, and each point is asked alone.
  bool allSeeWhole(std::span<const glm::vec3> points, const glm::vec3& eye) const;
  // The primitives that may enter the region around a block's pyramids to
  // any soft light, every light's joined (empty: allSeeWhole; none: a point
  // cannot be proved). Every primitive that may block one of the points is
  // among them, so that the point's own proof need ask only these:
  // seesWhole(p, eye, suspects) is seesWhole(p, eye) for each of them.
  std::optional<std::vector<std::uint32_t>> suspects(std::span<const glm::vec3> points, const glm::vec3& eye) const;
  bool seesWhole(const glm::vec3& p, const glm::vec3& eye, std::span<const std::uint32_t> suspects) const;

 private:
  // Whether a primitive the region query found may enter the pyramid (an
  // exact separating-axis test; the query's answer is conservative).
  bool blocks(std::uint32_t prim, const ConvexRegion& pyramid) const;
  struct SoftLight {
    std::array<glm::vec3, 4> corners;  // an area light's parallelogram
    glm::vec3 centre;
    glm::vec3 normal;     // an area light's: unit, towards the lit side
    float radius = 0.0f;  // a sphere light's (0: an area light)
    bool emitter = false;  // an emitting triangle: both sides lit, the pyramid short of it
  };
  // A pyramid's base: four corners in order around it, and the unit normal
  // of their plane towards the apex.
  struct Base {
    std::array<glm::vec3, 4> corners;
    glm::vec3 normal;
  };
  // The base from the apex (none: no proof from there).
  static std::optional<Base> baseFrom(const SoftLight& light, const glm::vec3& apex, float distance);
  // What p's proof of one light asks: nothing (the light sends p nothing),
  // the pyramid from the apex to the base through `centre`, or what cannot
  // be proved (no base).
  struct View {
    enum class Kind { kNothing, kPyramid, kUnprovable } kind = Kind::kNothing;
    glm::vec3 apex{0.0f};
    Base base;
    glm::vec3 centre{0.0f};
  };
  static View viewOf(SoftLight light, const glm::vec3& p, const glm::vec3& eye);
  static std::vector<glm::vec3> cornersAround(const SoftLight& light, const std::vector<View>& views);
  static ConvexRegion regionAround(const SoftLight& light, const std::vector<View>& views);
  // The pyramid from the apex to the base through `centre`, as a region.
  static ConvexRegion pyramidOf(const View& view);
  // Whether nothing enters the pyramid (of the primitives `suspects`, all
  // when none).
  bool clear(const View& view, std::optional<std::span<const std::uint32_t>> suspects) const;
  // seesWhole, asking `suspects` only (all primitives when none).
  bool seesWholeAsking(const glm::vec3& p, const glm::vec3& eye,
                       std::optional<std::span<const std::uint32_t>> suspects) const;
  // The views of every point that a light's proof asks about (none: one
  // cannot be proved).
  std::optional<std::vector<View>> viewsOf(const SoftLight& light, std::span<const glm::vec3> points,
                                           const glm::vec3& eye) const;
  const Geometry& geometry_;
  std::vector<SoftLight> lights_;
  Bvh bvh_;
};

}  // namespace glint::gl
