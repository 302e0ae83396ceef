#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "common/render/prepared_scene.h"
#include "server/lru_cache.h"

namespace glint::server {

// What a prepared scene holds in memory, roughly (geometry, BVH, textures).
std::size_t memoryFootprint(const PreparedScene& scene);

// Prepared scenes (scene + BVH) by the scene's hash, within --cache-mb.
class SceneCache : public LruCache<PreparedScene> {
 public:
  using LruCache::LruCache;
  void insert(const proto::SceneHash& hash, std::shared_ptr<const PreparedScene> scene) {
    const std::size_t bytes = memoryFootprint(*scene);
    LruCache::insert(hash, std::move(scene), bytes);
  }
};

// The files of uploaded scenes by their own SHA-256 (protocol 3), within
// --max-scene-mb: a file a server holds is not sent to it again, by any
// client, whatever scene names it.
class FileStore : public LruCache<std::string> {
 public:
  using LruCache::LruCache;
  void insert(const proto::SceneHash& hash, std::string bytes) {
    const std::size_t size = bytes.size();
    LruCache::insert(hash, std::make_shared<const std::string>(std::move(bytes)), size);
  }
};

}  // namespace glint::server
