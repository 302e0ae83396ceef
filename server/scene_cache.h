#pragma once

#include <cstddef>
#include <list>
#include <map>
#include <memory>
#include <mutex>

#include "common/prepared_scene.h"
#include "proto/scene_bundle.h"

namespace glint::server {

// Prepared scenes (scene + BVH) by content hash, under a memory bound: the
// least recently used scene goes first. A scene in use by a frame stays
// alive through its shared_ptr even after it leaves the cache.
class SceneCache {
 public:
  explicit SceneCache(std::size_t capacityBytes) : capacity_(capacityBytes) {}

  std::shared_ptr<const PreparedScene> find(const proto::SceneHash& hash);
  void insert(const proto::SceneHash& hash, std::shared_ptr<const PreparedScene> scene);
  std::size_t size() const;
  std::size_t bytes() const;

 private:
  struct Entry {
    std::shared_ptr<const PreparedScene> scene;
    std::size_t bytes;
    std::list<proto::SceneHash>::iterator age;
  };
  mutable std::mutex mutex_;
  std::size_t capacity_;
  std::size_t bytes_ = 0;
  std::map<proto::SceneHash, Entry> entries_;
  std::list<proto::SceneHash> recent_;  // front: most recently used
};

// What a prepared scene holds in memory, roughly (geometry, BVH, textures).
std::size_t memoryFootprint(const PreparedScene& scene);

}  // namespace glint::server
