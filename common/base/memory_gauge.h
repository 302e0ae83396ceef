#pragma once

#include <atomic>
#include <cstddef>
#include <string>

namespace glint {

// Memory shared by loads that run at once (glintd's scenes being built): each
// load draws its charges from it and gives them back when it is done.
class MemoryGauge {
 public:
  MemoryGauge(std::size_t capacityBytes, std::string name) : capacity_(capacityBytes), name_(std::move(name)) {}
  MemoryGauge(const MemoryGauge&) = delete;
  MemoryGauge& operator=(const MemoryGauge&) = delete;

  // Takes `bytes` if they fit; false (and nothing taken) otherwise.
  bool take(std::size_t bytes);
  void give(std::size_t bytes) { used_.fetch_sub(bytes); }
  std::size_t used() const { return used_.load(); }
  std::size_t capacity() const { return capacity_; }
  const std::string& name() const { return name_; }

 private:
  std::atomic<std::size_t> used_{0};
  std::size_t capacity_;
  std::string name_;
};

}  // namespace glint
