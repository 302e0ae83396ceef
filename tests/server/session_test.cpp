// The protocol state of one client without a socket: messages in, replies
// out, each rule of docs/protocol.md checked with byte vectors.
#include "server/session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "common/render/field_probes.h"
#include "common/render/renderer.h"
#include "proto/messages.h"
#include "server/log.h"
#include "tests/support/full_upload.h"
#include "tests/support/test_support.h"
#include "tests/support/inline_host.h"

namespace glint::server {
namespace {

class SessionTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { setLogging(false); }

  SessionTest()
      : cache_(std::size_t{64} << 20),
        files_(std::size_t{64} << 20),
        uploads_(std::size_t{32} << 20, "the test's upload gauge"),
        session_(host_, {cache_, files_, uploads_}, {1 << 20, 2, 8, std::size_t{16} << 20}, "test peer") {
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
  // What a client sends for a bundle the server lacks: each file's pieces
  // (of 4 KiB, so that a file takes several), then the scene.
  void upload(const proto::SceneBundle& bundle) {
    for (const auto& frame : proto::encodeFullUpload(bundle, 4096)) send(frame);
  }

  test::InlineHost host_;
  SceneCache cache_;
  FileStore files_;
  MemoryGauge uploads_;
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
  Session other(full, {cache_, files_, uploads_}, {1 << 20, 2, 8, 1 << 20}, "other");
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
  EXPECT_EQ(host_.workMessages, 0);  // Hello and a query keep no place
  const std::size_t uploadFrames = proto::encodeFullUpload(room.bundle, 4096).size();
  upload(room.bundle);
  EXPECT_EQ(host_.workMessages, static_cast<int>(uploadFrames));
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
  EXPECT_EQ(host_.workMessages, static_cast<int>(uploadFrames) + 2);
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
  upload(bad);
  EXPECT_EQ(errorCode(1), wire::ErrorCode::BadScene);
  EXPECT_EQ(session_.state(), Session::State::kServing);
  EXPECT_EQ(cache_.size(), 0u);
}

// A client builds one scene at a time: a second upload while the first is
// being built is refused (a client could otherwise queue builds ahead of
// every other client's), and once the first is done the next is taken.
TEST_F(SessionTest, ASecondUploadWhileTheFirstIsBuildingIsRefused) {
  hello();
  host_.deferBuilds = true;
  const proto::LoadedBundle room = proto::loadSceneBundle(glint::test::sourcePath("scenes/room.json"));
  const proto::SceneBundle other{room.bundle.text + " ", room.bundle.files};
  upload(room.bundle);
  const std::size_t before = host_.replies.size();
  upload(other);
  ASSERT_EQ(host_.replies.size(), before + 1);
  EXPECT_EQ(errorCode(before), wire::ErrorCode::UnknownMessage);
  EXPECT_EQ(host_.builds, 1);
  host_.finishBuilds();
  EXPECT_EQ(replyType(before + 1), wire::Body::SceneReady);
  upload(other);
  EXPECT_EQ(host_.builds, 2);
  EXPECT_EQ(session_.state(), Session::State::kServing);
}

// Files travel in pieces, by their hash: the bunny's mesh (220 KB, in 4 KiB
// pieces) is sent once; a changed scene that names it again is told that
// nothing is missing, and builds from the file the server kept.
TEST_F(SessionTest, FilesArriveInPiecesAndAreNotAskedForTwice) {
  hello();
  const proto::LoadedBundle bunny = proto::loadSceneBundle(glint::test::sourcePath("scenes/bunny.json"));
  const proto::BundleDigest digest = proto::digest(bunny.bundle);
  ASSERT_EQ(digest.files.size(), 1u);
  send(proto::encodeSceneQuery(digest.scene, digest.files));
  const auto* status = decode(host_.replies.at(1)).body_as_SceneStatus();
  ASSERT_TRUE(status && status->missing());
  EXPECT_FALSE(status->present());
  EXPECT_EQ(status->missing()->size(), 1u);
  upload(bunny.bundle);
  ASSERT_EQ(replyType(2), wire::Body::SceneReady);
  EXPECT_EQ(files_.size(), 1u);
  EXPECT_EQ(uploads_.used(), 0u);  // a complete file no longer draws on the upload memory

  proto::SceneBundle changed = bunny.bundle;
  changed.text.insert(changed.text.rfind('}'), ", \"background\": [0.1, 0.1, 0.1]");
  send(proto::encodeSceneQuery(changed.hash(), proto::digest(changed).files));
  status = decode(host_.replies.at(3)).body_as_SceneStatus();
  ASSERT_TRUE(status);
  EXPECT_FALSE(status->present());
  EXPECT_EQ(status->missing()->size(), 0u);  // the mesh is not sent again
  send(proto::encodeSceneUpload(changed.hash(), changed));
  EXPECT_EQ(replyType(4), wire::Body::SceneReady);
}

// Pieces out of order, over the size, over the limit, or whose whole does
// not match its hash are refused and leave nothing behind; a scene naming a
// file that never arrived is a BadScene; the session goes on.
TEST_F(SessionTest, HostileFilePiecesAreRefused) {
  hello();
  const std::string bytes(10000, 'v');
  const proto::SceneHash hash = proto::sha256(bytes);
  std::size_t replies = host_.replies.size();
  const auto refused = [&](const std::vector<std::uint8_t>& frame, const std::string& words) {
    send(frame);
    ASSERT_EQ(host_.replies.size(), replies + 1) << words;
    EXPECT_EQ(errorCode(replies), wire::ErrorCode::Malformed) << words;
    const std::string message = decode(host_.replies.at(replies)).body_as_Error()->message()->str();
    EXPECT_NE(message.find(words), std::string::npos) << message;
    ++replies;
    EXPECT_EQ(uploads_.used(), 0u) << words;
  };
  refused(proto::encodeFileChunk(hash, bytes.size(), 100, std::string_view(bytes).substr(0, 100)),
          "offset 100, expected 0 (pieces come in order)");
  refused(proto::encodeFileChunk(hash, 10, 0, bytes), "more bytes than the size 10");
  refused(proto::encodeFileChunk(hash, std::uint64_t{1} << 40, 0, "x"), "does not fit what this server holds");
  send(proto::encodeFileChunk(hash, bytes.size(), 0, std::string_view(bytes).substr(0, 5000)));
  EXPECT_EQ(uploads_.used(), 5000u);  // what arrived, not what was announced
  refused(proto::encodeFileChunk(hash, bytes.size(), 5000, std::string(5000, 'w')), "do not match its hash");
  EXPECT_EQ(files_.size(), 0u);

  const proto::SceneBundle scene{"{}", {{"mesh.obj", bytes}}};
  send(proto::encodeSceneUpload(scene.hash(), scene));
  EXPECT_EQ(errorCode(replies), wire::ErrorCode::BadScene);
  EXPECT_NE(decode(host_.replies.at(replies)).body_as_Error()->message()->str().find(
                "'mesh.obj' (" + proto::toHex(hash).substr(0, 12) + ") is not on this server"),
            std::string::npos);
  EXPECT_EQ(session_.state(), Session::State::kServing);
}

// Pieces of a file that never completes are given back when the session ends.
TEST_F(SessionTest, UnfinishedFilesAreGivenBackAtTheEnd) {
  {
    test::InlineHost host;
    Session other(host, {cache_, files_, uploads_}, {1 << 20, 2, 8, 1 << 20}, "other");
    host.attach(other);
    other.handle(decode(proto::encodeHello(1 << 20, 0, "test")));
    const std::string half(3000, 'h');
    other.handle(decode(proto::encodeFileChunk(proto::sha256("whatever"), 6000, 0, half)));
    EXPECT_EQ(uploads_.used(), 3000u);
  }
  EXPECT_EQ(uploads_.used(), 0u);
}

// A fill frame's tiles are batches of an irradiance field's probes, traced
// as buildField traces them in process; a frame that reads a field needs the
// whole field sent first (FieldPieces, in order), and then traces as the
// in-process tracer with that field. Pieces out of order or not finite are
// refused, and the field's memory is the uploads' while it is held.
TEST_F(SessionTest, FieldBatchesAndTheFieldFramesRead) {
  hello();
  const proto::LoadedBundle cornell = proto::loadSceneBundle(glint::test::sourcePath("scenes/cornell.json"));
  const proto::SceneHash hash = cornell.bundle.hash();
  upload(cornell.bundle);
  ASSERT_EQ(replyType(1), wire::Body::SceneReady);
  FrameSettings frame = cornell.scene.frame;
  frame.width = 16;
  frame.height = 16;
  frame.sampling.samples = 2;
  const FieldSettings settings{4, 64};
  const PreparedScene prepared(cornell.scene, BvhSettings{});
  RayStats rays;
  const IrradianceField local = buildField(prepared, frame, settings, rays);

  send(proto::encodeFrameSetup(7, hash, frame, {settings, true}));
  send(proto::encodeTileRequest(7, 0, {8, 0, 5, 1}, {}));
  const auto* batch = decode(host_.replies.at(2)).body_as_TileResult();
  ASSERT_TRUE(batch && batch->probes());
  ASSERT_EQ(batch->probes()->size(), 5u * IrradianceField::kProbeFloats);
  std::vector<float> expected(5 * IrradianceField::kProbeFloats);
  for (int i = 0; i < 5; ++i) {
    IrradianceField::writeProbe(local.probe(8 + i), std::span<float, IrradianceField::kProbeFloats>(
                                                        expected.data() + i * IrradianceField::kProbeFloats,
                                                        IrradianceField::kProbeFloats));
  }
  EXPECT_TRUE(std::equal(expected.begin(), expected.end(), batch->probes()->begin()));
  send(proto::encodeTileRequest(7, 1, {0, 0, 5, 2}, {}));
  EXPECT_EQ(errorCode(3), wire::ErrorCode::BadTile);

  send(proto::encodeFrameSetup(8, hash, frame, {settings, false}));
  EXPECT_EQ(errorCode(4), wire::ErrorCode::BadFrame);  // the field was not sent
  std::vector<std::vector<std::uint8_t>> pieces = proto::encodeFieldPieces(hash, local, 10000);
  ASSERT_GT(pieces.size(), 2u);
  send(pieces[1]);  // out of order
  EXPECT_EQ(errorCode(5), wire::ErrorCode::Malformed);
  for (const auto& piece : pieces) send(piece);
  EXPECT_EQ(host_.replies.size(), 6u);  // every piece taken in silence
  EXPECT_EQ(uploads_.used(), static_cast<std::size_t>(local.probeCount()) * sizeof(IrradianceField::Probe));
  send(proto::encodeFrameSetup(9, hash, frame, {settings, false}));
  send(proto::encodeTileRequest(9, 0, {0, 0, 16, 16}, {}));
  const auto* tile = decode(host_.replies.at(6)).body_as_TileResult();
  ASSERT_TRUE(tile && tile->rgb());
  const Renderer renderer(prepared, frame, EffectPlan::derive(prepared.scene(), frame), &local);
  std::vector<std::uint8_t> rgb;
  renderer.renderTile({0, 0, 16, 16}, {}, rgb, rays);
  EXPECT_TRUE(std::equal(rgb.begin(), rgb.end(), tile->rgb()->begin()) && rgb.size() == tile->rgb()->size());

  IrradianceField bad = local;
  bad.probe(0).irradiance[0].x = std::numeric_limits<float>::infinity();
  send(proto::encodeFieldPieces(hash, bad, 10000).front());
  EXPECT_EQ(errorCode(7), wire::ErrorCode::Malformed);
  EXPECT_EQ(uploads_.used(), 0u);  // the field refused is given back
  send(proto::encodeFrameSetup(10, hash, frame, {settings, false}));
  EXPECT_EQ(errorCode(8), wire::ErrorCode::BadFrame);
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
