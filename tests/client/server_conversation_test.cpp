// The client's side of the protocol with one server, without a socket:
// server messages in as byte vectors, what the client sends out, time as
// the waits it asks for and their ends.
#include "client/farm/server_conversation.h"

#include <limits>

#include <gtest/gtest.h>

#include "proto/messages.h"

namespace glint {
namespace {

// Records everything the conversation asks of its carrier.
struct RecordingHost : ConversationHost {
  std::vector<std::vector<std::uint8_t>> sent;
  std::vector<std::chrono::milliseconds> waits;  // each wait asked for
  bool waiting = false;
  int servings = 0;
  std::vector<std::pair<std::uint64_t, TileOutput>> results;
  std::vector<LinkFailure> failures;

  void send(std::vector<std::uint8_t> frame) override { sent.push_back(std::move(frame)); }
  void await(std::chrono::milliseconds timeout) override {
    waits.push_back(timeout);
    waiting = true;
  }
  void stopWaiting() override { waiting = false; }
  void serving() override { ++servings; }
  void delivered(std::uint32_t frameId, std::uint32_t tileId, TileOutput&& out) override {
    results.emplace_back(std::uint64_t{frameId} << 32 | tileId, std::move(out));
  }
  void lost(const LinkFailure& failure) override { failures.push_back(failure); }
};

class ServerConversationTest : public ::testing::Test {
 protected:
  ServerConversationTest()
      : bundle_{"{\"glint\": 1}", {{"a.obj", "v 0 0 0\n"}, {"b.obj", "v 1 1 1\n"}}},
        digest_(proto::digest(bundle_)),
        conversation_(host_, bundle_, digest_, {std::chrono::milliseconds(5000), std::chrono::milliseconds(9000)}) {}

  // Hands the conversation one server message, as its bytes decode.
  void receive(const std::vector<std::uint8_t>& frame) {
    const proto::Decoded d = proto::decodeFrame(frame, proto::kDefaultMaxMessageBytes, aligned_);
    ASSERT_EQ(d.status, proto::DecodeStatus::kGood) << d.error;
    conversation_.handle(*d.message);
  }
  wire::Body sentType(std::size_t i) {
    const proto::Decoded d = proto::decodeFrame(host_.sent.at(i), proto::kDefaultMaxMessageBytes, aligned_);
    return d.message->body_type();
  }
  // Connected, Hello answered by a server of this build: the scene query sent.
  void greet() {
    conversation_.start();
    conversation_.connected();
    receive(proto::encodeHello(1 << 20, 3, "test server"));
  }
  void serve() {
    greet();
    receive(proto::encodeSceneStatus(digest_.scene, true));
  }
  LinkFailure::Kind failure() const { return host_.failures.at(0).kind; }

  RecordingHost host_;
  proto::SceneBundle bundle_;
  proto::BundleDigest digest_;
  ServerConversation conversation_;
  std::vector<std::uint64_t> aligned_;
};

TEST_F(ServerConversationTest, HelloThenTheSceneQueryThenServingAServerThatHoldsTheScene) {
  conversation_.start();
  EXPECT_EQ(host_.waits, std::vector{std::chrono::milliseconds(5000)});  // connecting
  conversation_.connected();
  ASSERT_EQ(host_.sent.size(), 1u);
  EXPECT_EQ(sentType(0), wire::Body::Hello);
  receive(proto::encodeHello(1 << 20, 3, "test server"));
  ASSERT_EQ(host_.sent.size(), 2u);
  EXPECT_EQ(sentType(1), wire::Body::SceneQuery);
  EXPECT_EQ(conversation_.threads(), 3);
  receive(proto::encodeSceneStatus(digest_.scene, true));
  EXPECT_EQ(host_.servings, 1);
  EXPECT_FALSE(host_.waiting);
  EXPECT_FALSE(conversation_.uploaded());
  EXPECT_EQ(host_.sent.size(), 2u);  // nothing uploaded
}

TEST_F(ServerConversationTest, AServerOfAnotherBuildIsRefusedNamingBoth) {
  conversation_.start();
  conversation_.connected();
  receive(proto::encodeHello(1 << 20, 2, "test server", "another build"));
  ASSERT_EQ(host_.failures.size(), 1u);
  EXPECT_EQ(failure(), LinkFailure::Kind::kRefused);
  EXPECT_NE(host_.failures[0].what.find("server build 'another build'"), std::string::npos);
  EXPECT_TRUE(conversation_.over());
  EXPECT_FALSE(host_.waiting);
}

TEST_F(ServerConversationTest, OnlyTheFilesTheServerLacksAreSentOnceEachThenTheScene) {
  greet();
  const std::vector<std::uint32_t> missing{1, 1};  // asked twice: sent once
  receive(proto::encodeSceneStatus(digest_.scene, false, missing));
  ASSERT_EQ(host_.sent.size(), 4u);  // Hello, query, one chunk of b.obj, the upload
  EXPECT_EQ(sentType(2), wire::Body::FileChunk);
  EXPECT_EQ(sentType(3), wire::Body::SceneUpload);
  EXPECT_EQ(host_.sent[2], proto::encodeFileChunk(digest_.files[1], 8, 0, "v 1 1 1\n"));
  EXPECT_EQ(host_.waits.back(), std::chrono::milliseconds(9000));  // the scene's wait
  EXPECT_TRUE(conversation_.uploaded());
  conversation_.wrote(1000);  // the upload still moving: the wait starts again
  EXPECT_EQ(host_.waits.size(), 4u);
  receive(proto::encodeSceneReady(digest_.scene, 1.0f));
  EXPECT_EQ(host_.servings, 1);
}

TEST_F(ServerConversationTest, AFileIndexOutOfRangeIsBadBytes) {
  greet();
  const std::vector<std::uint32_t> missing{2};
  receive(proto::encodeSceneStatus(digest_.scene, false, missing));
  EXPECT_EQ(failure(), LinkFailure::Kind::kBadBytes);
  EXPECT_NE(host_.failures[0].what.find("asked for file 2 of a scene of 2 files"), std::string::npos);
}

TEST_F(ServerConversationTest, AResultMustAnswerARequestWithOneTriplePerMaskedPixel) {
  serve();
  const TileRect rect{0, 0, 4, 2};
  conversation_.request(1, 7, {rect, {}});
  const std::vector<std::uint8_t> rgb(4 * 2 * 3, 9);
  receive(proto::encodeTileResult(1, 7, rgb, {}, 1500));
  ASSERT_EQ(host_.results.size(), 1u);
  EXPECT_EQ(host_.results[0].first, std::uint64_t{1} << 32 | 7);
  EXPECT_EQ(host_.results[0].second.rgb, rgb);
  EXPECT_DOUBLE_EQ(host_.results[0].second.computeMs, 1.5);
  receive(proto::encodeTileResult(1, 7, rgb, {}, 1500));  // twice
  EXPECT_EQ(failure(), LinkFailure::Kind::kBadBytes);
  EXPECT_NE(host_.failures[0].what.find("tile 7 of frame 1, which was not asked of it"), std::string::npos);
}

TEST_F(ServerConversationTest, AResultOfTheWrongSizeIsBadBytes) {
  serve();
  conversation_.request(1, 0, {{0, 0, 4, 2}, {}});
  const std::vector<std::uint8_t> rgb(5, 0);
  receive(proto::encodeTileResult(1, 0, rgb, {}, 0));
  EXPECT_EQ(failure(), LinkFailure::Kind::kBadBytes);
  EXPECT_NE(host_.failures[0].what.find("with 5 bytes of pixels, not 24"), std::string::npos);
  EXPECT_TRUE(host_.results.empty());
}

// A fill frame's result carries its batch's probe values: as many as asked
// (the batch's probes times IrradianceField::kProbeFloats), every one finite.
TEST_F(ServerConversationTest, ABatchOfProbesMustCarryEachProbesFiniteValues) {
  serve();
  conversation_.setupFrame(2, FrameSettings{}, {FieldSettings{4, 64}, true});
  conversation_.request(2, 0, {{10, 0, 3, 1}, {}});
  conversation_.request(2, 1, {{13, 0, 3, 1}, {}});
  conversation_.request(2, 2, {{16, 0, 3, 1}, {}});
  std::vector<float> values(3 * IrradianceField::kProbeFloats, 0.5f);
  receive(proto::encodeTileResult(2, 0, {}, {}, 0, values));
  ASSERT_EQ(host_.results.size(), 1u);
  EXPECT_EQ(host_.results[0].second.probes, values);
  EXPECT_TRUE(host_.results[0].second.rgb.empty());
  values[7] = std::numeric_limits<float>::quiet_NaN();
  receive(proto::encodeTileResult(2, 1, {}, {}, 0, values));
  EXPECT_EQ(failure(), LinkFailure::Kind::kBadBytes);
  EXPECT_NE(host_.failures[0].what.find("tile 1 of frame 2 with probe values that are not finite"), std::string::npos)
      << host_.failures[0].what;
}

TEST_F(ServerConversationTest, ABatchWithTooFewProbeValuesIsBadBytes) {
  serve();
  conversation_.setupFrame(2, FrameSettings{}, {FieldSettings{4, 64}, true});
  conversation_.request(2, 0, {{0, 0, 3, 1}, {}});
  receive(proto::encodeTileResult(2, 0, {}, {}, 0, std::vector<float>(2 * IrradianceField::kProbeFloats, 1.0f)));
  EXPECT_EQ(failure(), LinkFailure::Kind::kBadBytes);
  EXPECT_NE(host_.failures[0].what.find("with 310 probe values, not 465"), std::string::npos)
      << host_.failures[0].what;
}

TEST_F(ServerConversationTest, AMessageOutOfTurnIsBadBytesAndNothingIsTakenAfter) {
  greet();
  receive(proto::encodeSceneReady(digest_.scene, 1.0f));  // before the scene status
  EXPECT_EQ(failure(), LinkFailure::Kind::kBadBytes);
  EXPECT_NE(host_.failures[0].what.find("unexpected SceneReady"), std::string::npos);
  receive(proto::encodeSceneStatus(digest_.scene, true));
  EXPECT_EQ(host_.servings, 0);
  EXPECT_EQ(host_.failures.size(), 1u);
}

TEST_F(ServerConversationTest, ErrorsSayWhetherTheSceneOrTheServerFailed) {
  greet();
  receive(proto::encodeError(wire::ErrorCode::BadScene, "objects[0].radius: must be > 0"));
  EXPECT_EQ(failure(), LinkFailure::Kind::kSceneError);
  EXPECT_NE(host_.failures[0].what.find("objects[0].radius"), std::string::npos);

  RecordingHost busyHost;
  ServerConversation busy(busyHost, bundle_, digest_, {});
  busy.start();
  busy.connected();
  const proto::Decoded d =
      proto::decodeFrame(proto::encodeError(wire::ErrorCode::Busy, "full"), proto::kDefaultMaxMessageBytes, aligned_);
  busy.handle(*d.message);
  EXPECT_EQ(busyHost.failures.at(0).kind, LinkFailure::Kind::kBusy);
}

TEST_F(ServerConversationTest, AWaitThatRunsOutNamesWhatItWaitedFor) {
  conversation_.start();
  conversation_.connected();
  conversation_.timedOut();
  EXPECT_EQ(failure(), LinkFailure::Kind::kUnreachable);
  EXPECT_EQ(host_.failures[0].what, "no answer within 5 s (Hello)");
}

TEST_F(ServerConversationTest, AStreamClosedBeforeHelloIsARefusalThatSuggestsTls) {
  conversation_.start();
  conversation_.connected();
  conversation_.streamEnded("closed the connection");
  EXPECT_EQ(failure(), LinkFailure::Kind::kRefused);
  EXPECT_NE(host_.failures[0].what.find("does it want TLS?"), std::string::npos);
}

TEST_F(ServerConversationTest, GoodbyeEndsTheConversationAndCancelsOnlyWhileServing) {
  greet();
  const std::vector<std::uint32_t> tiles{1};
  conversation_.cancel(1, tiles);  // not serving yet: nothing to cancel
  EXPECT_EQ(host_.sent.size(), 2u);
  receive(proto::encodeSceneStatus(digest_.scene, true));
  conversation_.cancel(1, tiles);
  EXPECT_EQ(sentType(2), wire::Body::Cancel);
  conversation_.close();
  EXPECT_EQ(sentType(3), wire::Body::Goodbye);
  EXPECT_EQ(conversation_.state(), ServerConversation::State::kClosed);
  conversation_.fail(LinkFailure::Kind::kStalled, "late");  // over: nothing more
  EXPECT_TRUE(host_.failures.empty());
}

}  // namespace
}  // namespace glint
