#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "common/scene/scene_budget.h"
#include "server/session.h"

namespace glint::server::test {

// A session's host without sockets or threads: replies are collected, builds
// and tiles run at once on the calling thread (tiles only up to a pixel x
// sample budget, so that a fuzzer's huge tiles are counted, not traced).
class InlineHost : public SessionHost {
 public:
  explicit InlineHost(std::size_t maxSceneBytes = std::size_t{64} << 20,
                      std::size_t maxTraceWork = std::size_t{1} << 16)
      : maxSceneBytes_(maxSceneBytes), maxTraceWork_(maxTraceWork), buildMemory_(maxSceneBytes, "the test gauge") {}

  void attach(Session& session) { session_ = &session; }

  void reply(std::vector<std::uint8_t> frame) override { replies.push_back(std::move(frame)); }
  void end(const std::string& why) override { ended = why; }
  bool admit() override { return admits; }
  void worked() override { ++workMessages; }
  void build(SceneJob job) override {
    ++builds;
    if (deferBuilds) {
      deferred_.push_back(std::move(job));
    } else {
      session_->sceneBuilt(buildScene(job, {maxSceneBytes_}, buildMemory_));
    }
  }
  // With deferBuilds, builds wait for this (as on glintd's build thread).
  void finishBuilds() {
    std::vector<SceneJob> jobs = std::move(deferred_);
    for (const SceneJob& job : jobs) session_->sceneBuilt(buildScene(job, {maxSceneBytes_}, buildMemory_));
  }
  void trace(TileWork work) override {
    ++tiles;
    const SessionFrame& frame = *work.frame;
    const std::size_t perUnit = static_cast<std::size_t>(frame.grid ? frame.grid->settings().rays
                                                                     : frame.renderer->frame().sampling.samples);
    if (work.rect.pixelCount() * perUnit <= maxTraceWork_) reply(traceTile(work));
  }

  void cancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds) override {
    cancelled.push_back({frameId, std::vector<std::uint32_t>(tileIds.begin(), tileIds.end())});
  }

  std::vector<std::vector<std::uint8_t>> replies;  // framed messages, in order
  std::vector<std::pair<std::uint32_t, std::vector<std::uint32_t>>> cancelled;  // frame, tiles
  std::string ended;                               // why the session ended, if it did
  bool admits = true;
  bool deferBuilds = false;
  int builds = 0;
  int tiles = 0;
  int workMessages = 0;  // messages that asked for work

 private:
  Session* session_ = nullptr;
  std::vector<SceneJob> deferred_;
  std::size_t maxSceneBytes_;
  std::size_t maxTraceWork_;
  MemoryGauge buildMemory_;
};

}  // namespace glint::server::test
