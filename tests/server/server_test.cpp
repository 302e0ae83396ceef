// glintd over loopback: the same pixels as in process, the scene cache, many
// clients, and every kind of bad input followed by a good client that is
// still served.
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <future>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "client/farm/distributed_tile_service.h"
#include "common/base/error.h"
#include "common/render/frame.h"
#include "tests/support/message_stream.h"
#include "proto/messages.h"
#include "server/log.h"
#include "tests/support/background_server.h"
#include "tests/support/test_support.h"
#include "tests/support/glintd_process.h"
#include "tests/server/raw_client.h"

namespace glint::server {
namespace {

using test::RawClient;

using namespace std::chrono_literals;

ServerOptions quickOptions() {
  ServerOptions o;
  o.listen = "127.0.0.1:0";
  o.threads = 2;
  o.handshakeTimeout = 500ms;
  o.readTimeout = 500ms;
  o.idleTimeout = 2s;
  o.handleSignals = false;
  return o;
}

// A glintd in this process with quick timeouts.
class TestServer : public BackgroundServer {
 public:
  explicit TestServer(const ServerOptions& o = quickOptions()) : BackgroundServer(o) {}
};

struct RoomFrame {
  proto::LoadedBundle loaded;
  FrameSettings frame;
};

RoomFrame smallRoom(const char* scene = "scenes/room.json") {
  RoomFrame r{proto::loadSceneBundle(glint::test::sourcePath(scene)), {}};
  r.frame = r.loaded.scene.frame;
  r.frame.width = 96;
  r.frame.height = 72;
  return r;
}

FrameImage localImage(const RoomFrame& r) {
  const PreparedScene prepared(r.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService service(prepared, pool);
  return renderFrame(service, r.frame, {}).image;
}

FrameImage remoteImage(const std::string& address, const RoomFrame& r) {
  DistributedTileService service(resolveServers({address}), r.loaded.bundle);
  return renderFrame(service, r.frame, {}).image;
}

class ServerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { setLogging(false); }
};

TEST_F(ServerTest, FramesThroughTheServerEqualInProcessFrames) {
  TestServer server;
  for (const char* scene : {"scenes/room.json", "scenes/glass.json", "scenes/bunny.json", "scenes/environment.json",
                            "scenes/sphere-light.json"}) {
    const RoomFrame r = smallRoom(scene);
    EXPECT_EQ(remoteImage(server.address(), r).rgb, localImage(r).rgb) << scene;
  }
  RoomFrame adaptive = smallRoom();
  adaptive.frame.sampling.pattern = SamplePattern::kAdaptive;
  adaptive.frame.sampling.samples = 9;
  EXPECT_EQ(remoteImage(server.address(), adaptive).rgb, localImage(adaptive).rgb) << "adaptive";
}

TEST_F(ServerTest, MaskedTilesEqualInProcessTiles) {
  TestServer server;
  const RoomFrame r = smallRoom();
  std::vector<TileJob> jobs;
  std::mt19937 rng(3);
  for (const TileRect& rect : tileGrid(r.frame.width, r.frame.height, 16)) {
    TileJob job{rect, std::vector<std::uint8_t>(maskByteCount(rect), 0)};
    for (std::size_t i = 0; i < rect.pixelCount(); ++i) {
      if (rng() % 3 == 0) setMaskBit(job.mask, i);
    }
    jobs.push_back(std::move(job));
  }
  jobs[2].mask.assign(jobs[2].mask.size(), 0);  // a tile with nothing to trace
  std::vector<std::vector<std::uint8_t>> local(jobs.size()), remote(jobs.size());
  const PreparedScene prepared(r.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService(prepared, pool).render(r.frame, jobs, [&](std::size_t i, TileOutput&& o) { local[i] = o.rgb; });
  DistributedTileService service(resolveServers({server.address()}), r.loaded.bundle);
  service.render(r.frame, jobs, [&](std::size_t i, TileOutput&& o) { remote[i] = o.rgb; });
  EXPECT_EQ(remote, local);
  EXPECT_TRUE(remote[2].empty());
  // On the wire: about 3 bytes per masked pixel plus mask bits and headers.
  std::size_t masked = 0, maskBytes = 0;
  for (const TileJob& j : jobs) {
    masked += countMasked(j.rect, j.mask);
    maskBytes += j.mask.size();
  }
  const ServerReport& t = service.lastFrame().servers.at(0);
  EXPECT_LT(t.bytesIn, masked * 3 + jobs.size() * 128 + 1024);
  EXPECT_GT(t.bytesIn, masked * 3);
}

TEST_F(ServerTest, SecondClientWithTheSameScenePaysNoUploadOrBuild) {
  TestServer server;
  const RoomFrame r = smallRoom();
  DistributedTileService first(resolveServers({server.address()}), r.loaded.bundle);
  EXPECT_TRUE(first.uploaded());
  DistributedTileService second(resolveServers({server.address()}), r.loaded.bundle);
  EXPECT_FALSE(second.uploaded());
  EXPECT_EQ(server.server().cache().size(), 1u);
}

TEST_F(ServerTest, ManyClientsAtOnce) {
  TestServer server;
  const RoomFrame r = smallRoom();
  const FrameImage expected = localImage(r);
  for (int clients : {2, 8}) {
    std::vector<std::future<FrameImage>> results;
    for (int i = 0; i < clients; ++i) {
      results.push_back(std::async(std::launch::async, [&] { return remoteImage(server.address(), r); }));
    }
    for (auto& f : results) EXPECT_EQ(f.get().rgb, expected.rgb) << clients;
  }
}

TEST_F(ServerTest, UnreachableServerSaysWhichAddressAndWhy) {
  const RoomFrame r = smallRoom();
  try {
    DistributedTileService service(resolveServers({"127.0.0.1:1"}), r.loaded.bundle);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("server 127.0.0.1:1: unreachable, cannot connect"), std::string::npos)
        << e.what();
  }
}

// Each bad input gets a clear error or a closed connection, and a good
// client right after it is still served.
class BadInputTest : public ServerTest {
 protected:
  BadInputTest() : r(smallRoom()), expected(localImage(r)), hash(r.loaded.bundle.hash()) {}
  void stillServes(const char* after) {
    EXPECT_EQ(remoteImage(server.address(), r).rgb, expected.rgb) << "after " << after;
  }

  TestServer server;
  const RoomFrame r;
  const FrameImage expected;
  const proto::SceneHash hash;
};

TEST_F(BadInputTest, BytesThatAreNotGlint) {
  {  // An HTTP request.
    RawClient c(server.port());
    c.write("GET / HTTP/1.1\r\nHost: localhost\r\n\r\n");
    EXPECT_EQ(c.readError().first, wire::ErrorCode::TooLarge);
    EXPECT_TRUE(c.closed());
  }
  stillServes("HTTP");
  {  // Random bytes with a plausible length.
    RawClient c(server.port());
    std::vector<std::uint8_t> junk = {64, 0, 0, 0};
    std::mt19937 rng(1);
    for (int i = 0; i < 64; ++i) junk.push_back(static_cast<std::uint8_t>(rng()));
    c.write(junk);
    EXPECT_EQ(c.readError().first, wire::ErrorCode::Malformed);
    EXPECT_TRUE(c.closed());
  }
  stillServes("random bytes");
  {  // A truncated frame, then silence: freed by the read timeout.
    RawClient c(server.port());
    c.write(std::vector<std::uint8_t>{100, 0, 0, 0, 1, 2, 3});
    EXPECT_TRUE(c.closed());
  }
  stillServes("truncated frame");
  {  // A client that connects and never speaks.
    RawClient c(server.port());
    EXPECT_TRUE(c.closed());
  }
  stillServes("silent client");
  {  // Oversized: over the server's limit, refused before reading the body.
    RawClient c(server.port());
    c.write(std::vector<std::uint8_t>{0, 0, 0, 0x10});  // 256 MiB announced
    EXPECT_EQ(c.readError().first, wire::ErrorCode::TooLarge);
    EXPECT_TRUE(c.closed());
  }
  stillServes("oversized frame");
}

TEST_F(BadInputTest, HandshakeErrorsEndTheConnection) {
  {  // Wrong protocol version.
    RawClient c(server.port());
    flatbuffers::FlatBufferBuilder b;
    const auto hello = wire::CreateHelloDirect(b, 99, 0, 0, "future");
    c.write(proto::finishFrame(b, wire::CreateMessage(b, wire::Body::Hello, hello.Union())));
    const auto [code, text] = c.readError();
    EXPECT_EQ(code, wire::ErrorCode::Version);
    EXPECT_NE(text.find("version 99"), std::string::npos);
    EXPECT_TRUE(c.closed());
  }
  {  // Anything before Hello.
    RawClient c(server.port());
    c.write(proto::encodeSceneQuery(hash));
    EXPECT_EQ(c.readError().first, wire::ErrorCode::UnknownMessage);
  }
  stillServes("handshake errors");
}

TEST_F(BadInputTest, ProtocolErrorsKeepTheConnection) {
  {  // Messages a server does not take, and references to unknown things:
     // errors, and the connection goes on.
    RawClient c(server.port());
    ASSERT_TRUE(c.hello());
    c.write(proto::encodeTileResult(1, 1, {}, {}, 0));
    EXPECT_EQ(c.readError().first, wire::ErrorCode::UnknownMessage);
    c.write(proto::encodeTileRequest(7, 1, {0, 0, 8, 8}, {}));
    EXPECT_EQ(c.readError().first, wire::ErrorCode::UnknownFrame);
    proto::SceneHash unknown{};
    c.write(proto::encodeFrameSetup(1, unknown, r.frame));
    EXPECT_EQ(c.readError().first, wire::ErrorCode::UnknownScene);
    // A scene that fails to load: the error names the JSON path.
    proto::SceneBundle bad{R"({"glint": 1, "image": {"width": 4, "height": 4},
        "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, "materials": {"m": {}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": -1, "material": "m"}]})", {}};
    c.write(proto::encodeSceneUpload(bad.hash(), bad));
    const auto [code, text] = c.readError();
    EXPECT_EQ(code, wire::ErrorCode::BadScene);
    EXPECT_NE(text.find("objects[0].radius: must be > 0"), std::string::npos) << text;
    // A bundle whose bytes do not match its hash.
    c.write(proto::encodeSceneUpload(unknown, r.loaded.bundle));
    EXPECT_EQ(c.readError().first, wire::ErrorCode::BadScene);
    // Now the real scene, then frames with bad values and bad tiles.
    c.write(proto::encodeSceneQuery(hash));
    ASSERT_TRUE(c.read());
    c.write(proto::encodeSceneUpload(hash, r.loaded.bundle));
    ASSERT_TRUE(c.read());  // SceneReady
    FrameSettings nan = r.frame;
    nan.camera.eye.x = std::nanf("");
    c.write(proto::encodeFrameSetup(2, hash, nan));
    const auto [nanCode, nanText] = c.readError();
    EXPECT_EQ(nanCode, wire::ErrorCode::BadFrame);
    EXPECT_NE(nanText.find("frame_setup.eye"), std::string::npos);
    c.write(proto::encodeFrameSetup(3, hash, r.frame));
    c.write(proto::encodeTileRequest(3, 1, {90, 0, 16, 16}, {}));
    EXPECT_EQ(c.readError().first, wire::ErrorCode::BadTile);
    c.write(proto::encodeTileRequest(3, 2, {0, 0, 8, 8}, std::vector<std::uint8_t>(3, 0xff)));
    EXPECT_EQ(c.readError().first, wire::ErrorCode::BadTile);
    // ...and a good tile on the same connection.
    c.write(proto::encodeTileRequest(3, 4, {0, 0, 8, 8}, {}));
    const wire::Message* result = c.read();
    ASSERT_TRUE(result && result->body_as_TileResult());
    EXPECT_EQ(result->body_as_TileResult()->rgb()->size(), 8u * 8u * 3u);
  }
  stillServes("bad messages");
}

// Cancel drops the frame's queued tiles: of 200 requested at once, only
// those already being traced come back, and the connection serves the
// next request (the results of the traced ones are not held back waiting
// for tiles that will never run).
TEST_F(ServerTest, CancelDropsQueuedTiles) {
  TestServer server;
  const RoomFrame r = smallRoom();
  const proto::SceneHash hash = r.loaded.bundle.hash();
  RawClient c(server.port());
  ASSERT_TRUE(c.hello());
  c.write(proto::encodeSceneUpload(hash, r.loaded.bundle));
  ASSERT_TRUE(c.read());  // SceneReady
  c.write(proto::encodeFrameSetup(1, hash, r.frame));
  std::vector<std::uint8_t> batch;
  constexpr std::uint32_t kTiles = 200;
  for (std::uint32_t t = 0; t < kTiles; ++t) {
    const auto request = proto::encodeTileRequest(1, t, {0, 0, r.frame.width, r.frame.height}, {});
    batch.insert(batch.end(), request.begin(), request.end());
  }
  const auto cancel = proto::encodeCancel(1, {});
  batch.insert(batch.end(), cancel.begin(), cancel.end());
  c.write(batch);
  c.write(proto::encodeTileRequest(1, 1000, {0, 0, 8, 8}, {}));
  std::uint32_t traced = 0;
  while (true) {
    const wire::Message* m = c.read();
    ASSERT_TRUE(m && m->body_as_TileResult()) << "no result for the request after the cancel";
    if (m->body_as_TileResult()->tile_id() == 1000) break;
    ++traced;
  }
  EXPECT_LT(traced, kTiles / 2);
}

// A client that asks for many tiles and never reads the results is dropped
// once its unread results pass the limit; others are served meanwhile.
TEST_F(ServerTest, ClientThatStopsReadingIsDropped) {
  ServerOptions o = quickOptions();
  o.maxQueuedBytes = 1 << 20;
  TestServer server(o);
  const RoomFrame r = smallRoom();
  const proto::SceneHash hash = r.loaded.bundle.hash();
  RawClient c(server.port());
  ASSERT_TRUE(c.hello());
  c.write(proto::encodeSceneQuery(hash));
  ASSERT_TRUE(c.read());
  c.write(proto::encodeSceneUpload(hash, r.loaded.bundle));
  ASSERT_TRUE(c.read());
  FrameSettings big = r.frame;
  big.width = 640;
  big.height = 480;
  big.sampling.samples = 1;
  big.sampling.pattern = SamplePattern::kRegular;
  c.write(proto::encodeFrameSetup(1, hash, big));
  // Far more results than the socket buffers and the 1 MiB limit hold.
  for (int round = 0; round < 8; ++round) {
    for (const TileRect& rect : tileGrid(640, 480, 64)) c.write(proto::encodeTileRequest(1, 0, rect, {}));
  }
  EXPECT_EQ(remoteImage(server.address(), r).rgb, localImage(r).rgb);
  EXPECT_TRUE(c.closed());
}

// SIGTERM during a frame: the real glintd stops accepting, cancels queued
// tiles, closes connections and exits 0; the client gets an error, not a hang.
TEST_F(ServerTest, SigtermDuringAFrame) {
  test::GlintdProcess glintd({"--threads", "2"});
  RoomFrame r = smallRoom();
  r.frame.width = 640;
  r.frame.height = 480;
  r.frame.sampling.samples = 64;
  auto render = std::async(std::launch::async, [&] {
    try {
      remoteImage(glintd.address(), r);
      return std::string("finished");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  });
  std::this_thread::sleep_for(500ms);
  const int status = glintd.stop(SIGTERM);
  ASSERT_TRUE(status >= 0 && WIFEXITED(status)) << "glintd did not exit after SIGTERM";
  EXPECT_EQ(WEXITSTATUS(status), 0);
  ASSERT_EQ(render.wait_for(10s), std::future_status::ready);
  EXPECT_NE(render.get().find("server 127.0.0.1:"), std::string::npos);
}

// What a client sent and glintd quotes in its log (a JSON key in a
// BadScene error) stays on its line: a key holding a newline and a
// timestamp once forged a log line of its own.
TEST(ServerLog, ClientTextCannotForgeALine) {
  setLogging(true);
  testing::internal::CaptureStderr();
  logLine("peer: error BadScene: materials.\"x\n2026-12-03T00:00:00.000Z glintd: stopped\": unknown key");
  const std::string out = testing::internal::GetCapturedStderr();
  setLogging(false);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
  EXPECT_NE(out.find("x\\n2026-12-03T00:00:00.000Z glintd: stopped"), std::string::npos) << out;
}

}  // namespace
}  // namespace glint::server
