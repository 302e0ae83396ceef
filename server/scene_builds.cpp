#include "server/scene_builds.h"

#include <algorithm>

namespace glint::server {

SceneBuilds::SceneBuilds(const BuildLimits& limits, MemoryGauge& buildMemory, int threads)
    : limits_(limits), buildMemory_(buildMemory), builders_(std::max(threads, 1)) {
  for (int i = 0; i < builders_.size(); ++i) builders_.submit([this] { run(); });
}

SceneBuilds::~SceneBuilds() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();  // each run() returns; the pool's destructor joins its workers
}

std::size_t SceneBuilds::built() const {
  std::lock_guard lock(mutex_);
  return built_;
}

void SceneBuilds::build(SceneJob job, Done done) {
  std::unique_lock lock(mutex_);
  if (const auto refused = refused_.find(job.hash); refused != refused_.end()) {
    BuiltScene again;
    again.hash = job.hash;
    again.error = refused->second;
    lock.unlock();
    done(again);
    return;
  }
  auto [waiting, fresh] = waiting_.try_emplace(job.hash);
  waiting->second.push_back(std::move(done));
  if (!fresh) return;  // queued or running already: this client waits for that build
  queue_.push_back(std::move(job));
  lock.unlock();
  wake_.notify_one();
}

void SceneBuilds::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (stopping_) return;
    const SceneJob job = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    const BuiltScene built = buildScene(job, limits_, buildMemory_);
    lock.lock();
    ++built_;
    if (!built.prepared && built.lasting) remember(built);
    std::vector<Done> waiting = std::move(waiting_[job.hash]);
    waiting_.erase(job.hash);
    lock.unlock();
    for (const Done& done : waiting) done(built);
    lock.lock();
  }
}

void SceneBuilds::remember(const BuiltScene& built) {
  if (!refused_.emplace(built.hash, built.error).second) return;
  refusedOrder_.push_back(built.hash);
  if (refusedOrder_.size() > kRefusalsRemembered) {
    refused_.erase(refusedOrder_.front());
    refusedOrder_.pop_front();
  }
}

}  // namespace glint::server
