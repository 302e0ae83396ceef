#pragma once

#include <map>
#include <memory>
#include <string>

#include "common/base/file_source.h"
#include "common/scene/texture.h"
#include "common/scene/scene_budget.h"

namespace glint {

// The images of one scene's load, by path: each file read, decoded and
// charged to the scene's budget once, however many textures name it (the
// scene's own, and the materials of its mesh files: many materials of one
// asset often share one atlas).
class ImageCache {
 public:
  ImageCache(FileSource& files, SceneBudget& budget) : files_(files), budget_(budget) {}
  ImageCache(const ImageCache&) = delete;
  ImageCache& operator=(const ImageCache&) = delete;

  // The image at `path` (normalised); errors start with `place`.
  std::shared_ptr<const Image> get(const std::string& path, const std::string& place);

 private:
  FileSource& files_;
  SceneBudget& budget_;
  std::map<std::string, std::shared_ptr<const Image>> images_;
};

}  // namespace glint
