// A farm that changes while glint renders: `glint render --frames 30
// --server-file FILE` through real glintd processes on loopback, with a
// server added to FILE after frame 5 and another removed after frame 10.
// What the --stats records say of each frame is checked, and the last image
// against the in-process render, byte for byte.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/glint_run.h"
#include "tests/support/glintd_process.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using server::test::GlintdProcess;

class ElasticFarm : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / "glint_elastic_farm";
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // Replaces the server file at once, as docs/distributed.md advises (a
  // new file renamed over the old).
  void publish(const std::vector<const GlintdProcess*>& servers) const {
    {
      std::ofstream out(path("servers.new"));
      out << "# the farm\n";
      for (const GlintdProcess* s : servers) out << s->address() << '\n';
    }
    fs::rename(path("servers.new"), path("servers.txt"));
  }

  // The --stats records written so far, one per frame done.
  std::vector<nlohmann::json> records() const {
    std::vector<nlohmann::json> out;
    std::ifstream in(path("stats.jsonl"));
    std::string line;
    while (std::getline(in, line)) {
      if (nlohmann::json::accept(line)) out.push_back(nlohmann::json::parse(line));
    }
    return out;
  }

  // Waits (at most a minute) until `frames` frames are done.
  bool awaitFrames(std::size_t frames) const {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    while (records().size() < frames) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return true;
  }

  fs::path dir_;
};

// The record's row for a server, or null when the frame has none.
const nlohmann::json* rowOf(const nlohmann::json& record, const GlintdProcess& server) {
  for (const nlohmann::json& s : record["servers"]) {
    if (s["address"] == server.address()) return &s;
  }
  return nullptr;
}

TEST_F(ElasticFarm, ServersJoinAndLeaveBetweenFramesAndTheImageStaysTheSame) {
  const GlintdProcess a({"--threads", "1"}), b({"--threads", "1"}), c({"--threads", "1"});
  publish({&a, &b});
  const std::string frame = std::string(GLINT_SOURCE_DIR) + "/scenes/room.json --mask all --size 320x240";
  // A server slowed by a loaded machine (ctest -j2) must not count as
  // stalled and be dropped: this test is about servers joining and leaving.
  std::future<test::GlintRun> farm = std::async(std::launch::async, [&] {
    return test::runGlint("render " + frame + " --frames 30 --stall-timeout 60 --server-file " + path("servers.txt") +
                          " --stats " + path("stats.jsonl") + " -o " + path("farm.png"));
  });
  ASSERT_TRUE(awaitFrames(5));
  publish({&a, &b, &c});
  ASSERT_TRUE(awaitFrames(10));
  publish({&a, &c});
  const test::GlintRun run = farm.get();
  ASSERT_EQ(run.status, 0) << run.output;

  const std::vector<nlohmann::json> frames = records();
  ASSERT_EQ(frames.size(), 30u);
  std::size_t joinedAt = 0;
  std::size_t leftAt = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const nlohmann::json* row = rowOf(frames[f], c);
    if (row && (*row)["joined"] == true) joinedAt = f;
    row = rowOf(frames[f], b);
    if (row && (*row)["state"] == "left") leftAt = f;
  }
  EXPECT_GE(joinedAt, 5u);  // listed once frame 5 was done
  EXPECT_GE(leftAt, 10u);
  int tilesOfC = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const nlohmann::json* added = rowOf(frames[f], c);
    EXPECT_EQ(added != nullptr, f >= joinedAt) << "frame " << f;
    if (added) tilesOfC += (*added)["tiles"].get<int>();
    const nlohmann::json* removed = rowOf(frames[f], b);
    EXPECT_EQ(removed != nullptr, f <= leftAt) << "frame " << f;  // in the table until the frame it left
    if (f == leftAt) {
      EXPECT_EQ((*removed)["tiles"], 0);
    }
    EXPECT_EQ((*rowOf(frames[f], a))["state"], "ok") << "frame " << f;
  }
  EXPECT_GT(tilesOfC, 0);
  EXPECT_GT((*rowOf(frames.back(), c))["tiles"].get<int>(), 0);

  const test::GlintRun here = test::runGlint("render " + frame + " -o " + path("here.png"));
  ASSERT_EQ(here.status, 0) << here.output;
  EXPECT_EQ(test::decodePngFile(path("farm.png")).rgb, test::decodePngFile(path("here.png")).rgb);
}

}  // namespace
}  // namespace glint
