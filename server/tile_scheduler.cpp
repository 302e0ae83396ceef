#include "server/tile_scheduler.h"

namespace glint::server {

TileScheduler::~TileScheduler() {
  std::unique_lock lock(mutex_);
  queues_.clear();
  turn_.clear();
  queued_ = 0;
  idle_.wait(lock, [this] { return inPool_ == 0; });
}

void TileScheduler::submit(std::uint64_t client, std::function<void()> task, Tag tag) {
  {
    std::lock_guard lock(mutex_);
    auto& queue = queues_[client];
    if (queue.empty()) turn_.push_back(client);
    queue.push_back({std::move(task), tag});
    ++queued_;
    ++inPool_;
  }
  // Each submitted task adds one "run the next task in turn" to the pool.
  pool_.submit([this] {
    runOne();
    std::lock_guard lock(mutex_);
    if (--inPool_ == 0) idle_.notify_all();
  });
}

void TileScheduler::runOne() {
  std::function<void()> task;
  {
    std::lock_guard lock(mutex_);
    if (turn_.empty()) return;  // its task was cancelled
    const std::uint64_t client = turn_.front();
    turn_.pop_front();
    auto it = queues_.find(client);
    task = std::move(it->second.front().run);
    it->second.pop_front();
    --queued_;
    if (it->second.empty()) {
      queues_.erase(it);
    } else {
      turn_.push_back(client);
    }
  }
  task();
}

std::size_t TileScheduler::cancel(std::uint64_t client) {
  std::lock_guard lock(mutex_);
  const auto it = queues_.find(client);
  if (it == queues_.end()) return 0;
  const std::size_t n = it->second.size();
  queued_ -= n;
  queues_.erase(it);
  std::erase(turn_, client);
  return n;
}

std::size_t TileScheduler::cancel(std::uint64_t client, const std::function<bool(std::uint64_t)>& which) {
  std::lock_guard lock(mutex_);
  const auto it = queues_.find(client);
  if (it == queues_.end()) return 0;
  const std::size_t n = std::erase_if(it->second, [&which](const Task& t) { return t.tag && which(*t.tag); });
  queued_ -= n;
  if (it->second.empty()) {
    queues_.erase(it);
    std::erase(turn_, client);
  }
  return n;
}

std::size_t TileScheduler::queued() const {
  std::lock_guard lock(mutex_);
  return queued_;
}

}  // namespace glint::server
