// The protocol state of one client without a socket: messages in, replies
// out, each rule of docs/protocol.md checked with byte vectors.
#include "server/session.h"

#include <gtest/gtest.h>

#include "proto/messages.h"
#include "server/log.h"
#include "tests/common/test_support.h"
#include "tests/server/inline_host.h"

namespace glint::server {
namespace {

class SessionTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { setLogging(false); }

  SessionTest() : cache_(std::size_t{64} << 20), session_(host_, cache_, {1 << 20, 2, 8}, "test peer") {
    host_.attach(session_);
  }

  // The message of an encoded frame, valid until the next call.
  const wire::Message& decode(const std::vector<std::uint8_t>& frame) {
    const proto::Decoded d = proto::decodeFrame(frame, proto::kDefaultMaxMessageBytes, aligned_);
    EXPECT_EQ(d.status, proto::DecodeStatus::kGood) << d.error;
    return *d.message;
  }
  // Sends one encoded frame to the session.
  void send(const std::vector<std::uint8_t>& frame) { session_.handle(decode(frame)); }
  wire::Body replyType(std::size_t i) { return decode(host_.replies.at(i)).body_type(); }
  wire::ErrorCode errorCode(std::size_t i) {
    const auto* e = decode(host_.replies.at(i)).body_as_Error();
    return e ? e->code() : wire::ErrorCode::Internal;
  }
  void hello() { send(proto::encodeHello(1 << 20, 0, "test")); }

  std::vector<std::uint64_t> aligned_;
  test::InlineHost host_;
  SceneCache cache_;
  Session session_;
};

TEST_F(SessionTest, HelloFirstOrTheSessionEnds) {
  send(proto::encodeSceneQuery({}));
  ASSERT_EQ(host_.replies.size(), 1u);
  EXPECT_EQ(errorCode(0), wire::ErrorCode::UnknownMessage);
  EXPECT_EQ(session_.state(), Session::State::kEnded);
  EXPECT_FALSE(host_.ended.empty());
  hello();  // ignored once ended
  EXPECT_EQ(host_.replies.size(), 1u);
}

TEST_F(SessionTest, HelloIsAnsweredOnceAndAFullServerSaysBusy) {
  hello();
  EXPECT_EQ(replyType(0), wire::Body::Hello);
  EXPECT_EQ(session_.state(), Session::State::kServing);
  hello();
  EXPECT_EQ(errorCode(1), wire::ErrorCode::UnknownMessage);
  EXPECT_EQ(session_.state(), Session::State::kServing);

  test::InlineHost full;
  full.admits = false;
  Session other(full, cache_, {1 << 20, 2, 8}, "other");
  const auto frame = proto::encodeHello(1 << 20, 0, "test");
  other.handle(decode(frame));
  EXPECT_EQ(other.state(), Session::State::kEnded);
  const auto* error = decode(full.replies.at(0)).body_as_Error();
  ASSERT_TRUE(error);
  EXPECT_EQ(error->code(), wire::ErrorCode::Busy);
  EXPECT_NE(error->message()->str().find("maximum of 8 clients"), std::string::npos);
}

TEST_F(SessionTest, UploadBuildsTheSceneAndTilesAreTraced) {
  hello();
  const proto::LoadedBundle room = proto::loadSceneBundle(glint::test::sourcePath("scenes/room.json"));
  const proto::SceneHash hash = room.bundle.hash();
  send(proto::encodeSceneQuery(hash));
  EXPECT_EQ(replyType(1), wire::Body::SceneStatus);
  send(proto::encodeSceneUpload(hash, room.bundle));
  EXPECT_EQ(host_.builds, 1);
  EXPECT_EQ(replyType(2), wire::Body::SceneReady);
  EXPECT_TRUE(cache_.find(hash));

  FrameSettings frame = room.scene.frame;
  frame.width = 32;
  frame.height = 16;
  frame.sampling.samples = 1;
  frame.sampling.pattern = SamplePattern::kRegular;
  send(proto::encodeFrameSetup(5, hash, frame));
  EXPECT_EQ(host_.replies.size(), 3u);  // a good setup has no answer
  send(proto::encodeTileRequest(5, 0, {0, 0, 16, 16}, {}));
  EXPECT_EQ(host_.tiles, 1);
  EXPECT_EQ(replyType(3), wire::Body::TileResult);
  send(proto::encodeTileRequest(6, 0, {0, 0, 16, 16}, {}));
  EXPECT_EQ(errorCode(4), wire::ErrorCode::UnknownFrame);
  send(proto::encodeTileRequest(5, 1, {24, 0, 16, 16}, {}));
  EXPECT_EQ(errorCode(5), wire::ErrorCode::BadTile);
  EXPECT_EQ(host_.tiles, 1);

  send(proto::encodeGoodbye());
  EXPECT_EQ(session_.state(), Session::State::kEnded);
  EXPECT_EQ(host_.ended, "goodbye");
}

TEST_F(SessionTest, BadSceneIsAnErrorAndTheSessionGoesOn) {
  hello();
  proto::SceneBundle bad{"{\"glint\": 1, \"image\": {\"width\": 1e999}}", {}};
  send(proto::encodeSceneUpload(bad.hash(), bad));
  EXPECT_EQ(errorCode(1), wire::ErrorCode::BadScene);
  EXPECT_EQ(session_.state(), Session::State::kServing);
  EXPECT_EQ(cache_.size(), 0u);
}

// Cancel names the frame and its tiles (none: the whole frame) and is handed
// to the host, which drops what is still queued; it gets no reply. The
// server's Hello carries its build identity.
TEST_F(SessionTest, CancelReachesTheHostAndHelloNamesTheBuild) {
  hello();
  const auto* serverHello = decode(host_.replies.at(0)).body_as_Hello();
  ASSERT_TRUE(serverHello && serverHello->build());
  EXPECT_EQ(serverHello->build()->str(), buildIdentity());
  const std::vector<std::uint32_t> tiles{3, 5};
  send(proto::encodeCancel(7, tiles));
  send(proto::encodeCancel(8, {}));
  ASSERT_EQ(host_.cancelled.size(), 2u);
  EXPECT_EQ(host_.cancelled[0], (std::pair<std::uint32_t, std::vector<std::uint32_t>>{7, tiles}));
  EXPECT_EQ(host_.cancelled[1], (std::pair<std::uint32_t, std::vector<std::uint32_t>>{8, {}}));
  EXPECT_EQ(host_.replies.size(), 1u);
}

}  // namespace
}  // namespace glint::server
