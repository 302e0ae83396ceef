// glintd's scene builds: one build for every client that uploads the same
// scene while it is queued or running; a scene refused for what it is
// refused again from memory; a refusal for memory others held, or of bytes
// that are not their hash's, is not remembered; the builds run off the
// tracing pool (hostile_client_test shows tiles going on meanwhile).
#include "server/scene_builds.h"

#include <future>

#include <gtest/gtest.h>

#include "proto/scene_bundle.h"
#include "tests/support/test_support.h"

namespace glint::server {
namespace {

SceneJob job(const proto::SceneBundle& bundle) {
  return {bundle.hash(), std::make_shared<const proto::SceneBundle>(bundle)};
}

const proto::SceneBundle& room() {
  static const proto::LoadedBundle loaded = proto::loadSceneBundle(glint::test::sourcePath("scenes/room.json"));
  return loaded.bundle;
}

// Waits for a result that another thread sets.
struct Outcome {
  std::promise<BuiltScene> promise;
  std::future<BuiltScene> future = promise.get_future();
  SceneBuilds::Done done() {
    return [this](const BuiltScene& built) { promise.set_value(built); };
  }
};

// A gigabyte for each scene and for the builds together.
class SceneBuildsTest : public ::testing::Test {
 protected:
  MemoryGauge gauge{std::size_t{1} << 30, "the test gauge"};
  SceneBuilds builds{{std::size_t{1} << 30}, gauge};
};

TEST_F(SceneBuildsTest, UploadsOfOneSceneWhileItIsQueuedAreBuiltOnce) {
  // The first build's answer holds the builder until both copies of the
  // second scene are asked for.
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  Outcome first, a, b;
  builds.build(job(proto::SceneBundle{"{}", {}}), [&first, released](const BuiltScene& built) {
    released.wait();
    first.promise.set_value(built);
  });
  builds.build(job(room()), a.done());
  builds.build(job(room()), b.done());
  release.set_value();
  const BuiltScene fromA = a.future.get();
  const BuiltScene fromB = b.future.get();
  ASSERT_NE(fromA.prepared, nullptr) << fromA.error;
  EXPECT_EQ(fromA.prepared, fromB.prepared);  // one build, told to both
  EXPECT_EQ(builds.built(), 2u);
  EXPECT_FALSE(first.future.get().error.empty());
}

// With two threads a long build does not hold a second one back.
TEST(SceneBuildsThreads, TwoThreadsBuildTwoScenesAtOnce) {
  MemoryGauge gauge{std::size_t{1} << 30, "the test gauge"};
  SceneBuilds two{{std::size_t{1} << 30}, gauge, 2};
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  Outcome held, other;
  two.build(job(proto::SceneBundle{"{}", {}}), [&, released](const BuiltScene& built) {
    released.wait();
    held.promise.set_value(built);
  });
  two.build(job(room()), other.done());
  EXPECT_EQ(other.future.wait_for(std::chrono::seconds(30)), std::future_status::ready);  // while the first is held
  release.set_value();
  held.future.get();
  EXPECT_EQ(SceneBuilds::threadsBeside(1), 1);
  EXPECT_EQ(SceneBuilds::threadsBeside(2), 2);
  EXPECT_EQ(SceneBuilds::threadsBeside(64), SceneBuilds::kMaxThreads);
}

TEST_F(SceneBuildsTest, ASceneRefusedForWhatItIsIsRefusedAgainWithoutABuild) {
  const proto::SceneBundle bad{R"({"glint": 1, "objects": [{"type": "sphere", "radius": -1}]})", {}};
  Outcome once, again;
  builds.build(job(bad), once.done());
  const BuiltScene refused = once.future.get();
  ASSERT_EQ(refused.prepared, nullptr);
  EXPECT_TRUE(refused.lasting);
  builds.build(job(bad), again.done());
  EXPECT_EQ(again.future.get().error, refused.error);
  EXPECT_EQ(builds.built(), 1u);
}

TEST_F(SceneBuildsTest, ASceneRefusedForMemoryOthersHeldIsBuiltAgainWhenItComesBack) {
  ASSERT_TRUE(gauge.take(gauge.capacity()));  // other builds hold it all
  Outcome once, again;
  builds.build(job(room()), once.done());
  const BuiltScene refused = once.future.get();
  EXPECT_FALSE(refused.lasting);
  EXPECT_NE(refused.error.find("try again later"), std::string::npos) << refused.error;
  gauge.give(gauge.capacity());
  builds.build(job(room()), again.done());
  EXPECT_NE(again.future.get().prepared, nullptr);
  EXPECT_EQ(builds.built(), 2u);
}

// A client that uploads other bytes under a scene's hash is refused, and
// the refusal is not remembered for that hash: the real scene, uploaded
// next, builds (remembering it would let anyone refuse a scene to everyone).
TEST_F(SceneBuildsTest, BytesThatAreNotTheHashsDoNotRefuseTheRealScene) {
  Outcome forged, real;
  builds.build({room().hash(), std::make_shared<const proto::SceneBundle>(proto::SceneBundle{"{}", {}})},
               forged.done());
  const BuiltScene refused = forged.future.get();
  EXPECT_NE(refused.error.find("do not match its hash"), std::string::npos) << refused.error;
  EXPECT_FALSE(refused.lasting);
  builds.build(job(room()), real.done());
  EXPECT_NE(real.future.get().prepared, nullptr);
  EXPECT_EQ(builds.built(), 2u);
}

TEST_F(SceneBuildsTest, ARefusalQuotingAHugeKeyIsCut) {
  const proto::SceneBundle bad{"{\"glint\": 1, \"" + std::string(1 << 20, 'k') + "\": 0}", {}};
  Outcome once;
  builds.build(job(bad), once.done());
  const BuiltScene refused = once.future.get();
  ASSERT_EQ(refused.prepared, nullptr);
  EXPECT_LE(refused.error.size(), kMaxErrorBytes + 16);
  EXPECT_NE(refused.error.find("... (cut)"), std::string::npos);
}

}  // namespace
}  // namespace glint::server
