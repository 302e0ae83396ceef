#pragma once

#include "common/geometry/bvh.h"
#include "common/scene/scene.h"

namespace glint {

// A scene with its BVH: built once, then shared read-only by every frame and
// thread that renders it (and cached by the server under the scene's hash).
class PreparedScene {
 public:
  PreparedScene(Scene scene, const BvhSettings& settings)
      : scene_(std::move(scene)), bvh_(Bvh::build(scene_.geometry, settings)) {}
  // The BVH refers to this object's geometry: it stays where it was built.
  PreparedScene(const PreparedScene&) = delete;
  PreparedScene& operator=(const PreparedScene&) = delete;

  const Scene& scene() const { return scene_; }
  const Bvh& bvh() const { return bvh_; }

 private:
  Scene scene_;
  Bvh bvh_;
};

}  // namespace glint
