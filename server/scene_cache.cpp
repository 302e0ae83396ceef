#include "server/scene_cache.h"

#include "common/scene_budget.h"

namespace glint::server {

std::size_t memoryFootprint(const PreparedScene& p) {
  const Scene& s = p.scene();
  const Geometry& g = s.geometry;
  // The per-item costs the loader charged (SceneBudget), with the BVH as built.
  std::size_t bytes = g.positions().size() * SceneBudget::kBytesPerVertex +
                      g.triangles().size() * SceneBudget::kBytesPerTriangle +
                      g.spheres().size() * SceneBudget::kBytesPerSphere +
                      p.bvh().nodes().size() * sizeof(BvhNode) + p.bvh().primIds().size() * sizeof(std::uint32_t);
  for (const Texture& t : s.textures) {
    if (t.image) bytes += t.image->rgb.size();
  }
  return bytes + 4096;
}

std::shared_ptr<const PreparedScene> SceneCache::find(const proto::SceneHash& hash) {
  std::lock_guard lock(mutex_);
  const auto it = entries_.find(hash);
  if (it == entries_.end()) return nullptr;
  recent_.splice(recent_.begin(), recent_, it->second.age);
  return it->second.scene;
}

void SceneCache::insert(const proto::SceneHash& hash, std::shared_ptr<const PreparedScene> scene) {
  std::lock_guard lock(mutex_);
  if (const auto old = entries_.find(hash); old != entries_.end()) {
    bytes_ -= old->second.bytes;
    recent_.erase(old->second.age);
    entries_.erase(old);
  }
  const std::size_t size = memoryFootprint(*scene);
  recent_.push_front(hash);
  entries_[hash] = {std::move(scene), size, recent_.begin()};
  bytes_ += size;
  // Evict the least recently used, but never the scene just inserted.
  while (bytes_ > capacity_ && recent_.size() > 1) {
    const auto victim = entries_.find(recent_.back());
    bytes_ -= victim->second.bytes;
    entries_.erase(victim);
    recent_.pop_back();
  }
}

std::size_t SceneCache::size() const {
  std::lock_guard lock(mutex_);
  return entries_.size();
}

std::size_t SceneCache::bytes() const {
  std::lock_guard lock(mutex_);
  return bytes_;
}

}  // namespace glint::server
