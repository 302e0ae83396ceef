#pragma once

#include <mutex>
#include <optional>

#include "common/geometry/bvh.h"
#include "common/render/environment_light.h"
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
  // The environment image as a light (path transport samples it), made once,
  // when a frame first asks; nullptr where the scene has none or it is black.
  const EnvironmentLight* environmentLight() const;

 private:
  Scene scene_;
  Bvh bvh_;
  mutable std::once_flag skyOnce_;
  mutable std::optional<EnvironmentLight> sky_;
};

}  // namespace glint
