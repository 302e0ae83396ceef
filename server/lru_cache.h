#pragma once

#include <cstddef>
#include <list>
#include <map>
#include <memory>
#include <mutex>

#include "proto/scene_bundle.h"

namespace glint::server {

// Values by content hash under a memory bound, shared by every connection:
// the least recently used goes first, never the one just inserted. A value
// in use stays alive through its shared_ptr after it leaves the cache.
template <typename Value>
class LruCache {
 public:
  explicit LruCache(std::size_t capacityBytes) : capacity_(capacityBytes) {}

  std::shared_ptr<const Value> find(const proto::SceneHash& hash) {
    std::lock_guard lock(mutex_);
    const auto it = entries_.find(hash);
    if (it == entries_.end()) return nullptr;
    recent_.splice(recent_.begin(), recent_, it->second.age);
    return it->second.value;
  }

  void insert(const proto::SceneHash& hash, std::shared_ptr<const Value> value, std::size_t bytes) {
    std::lock_guard lock(mutex_);
    if (const auto old = entries_.find(hash); old != entries_.end()) {
      bytes_ -= old->second.bytes;
      recent_.erase(old->second.age);
      entries_.erase(old);
    }
    recent_.push_front(hash);
    entries_[hash] = {std::move(value), bytes, recent_.begin()};
    bytes_ += bytes;
    while (bytes_ > capacity_ && recent_.size() > 1) {
      const auto victim = entries_.find(recent_.back());
      bytes_ -= victim->second.bytes;
      entries_.erase(victim);
      recent_.pop_back();
    }
  }

  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return entries_.size();
  }
  std::size_t bytes() const {
    std::lock_guard lock(mutex_);
    return bytes_;
  }

 private:
  struct Entry {
    std::shared_ptr<const Value> value;
    std::size_t bytes;
    typename std::list<proto::SceneHash>::iterator age;
  };
  mutable std::mutex mutex_;
  std::size_t capacity_;
  std::size_t bytes_ = 0;
  std::map<proto::SceneHash, Entry> entries_;
  std::list<proto::SceneHash> recent_;  // front: most recently used
};

}  // namespace glint::server
