#include "common/render/prepared_scene.h"

namespace glint {

const EnvironmentLight* PreparedScene::environmentLight() const {
  std::call_once(skyOnce_, [this] {
    if (scene_.environment) sky_.emplace(*scene_.environment);
    if (sky_ && sky_->empty()) sky_.reset();
  });
  return sky_ ? &*sky_ : nullptr;
}

}  // namespace glint
