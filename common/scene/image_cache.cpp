#include "common/scene/image_cache.h"

#include "common/image/image_decode.h"

namespace glint {

std::shared_ptr<const Image> ImageCache::get(const std::string& path, const std::string& place) {
  if (const auto held = images_.find(path); held != images_.end()) return held->second;
  auto image = std::make_shared<const Image>(decodeImage(files_.read(path, place), place, budget_));
  images_.emplace(path, image);
  return image;
}

}  // namespace glint
