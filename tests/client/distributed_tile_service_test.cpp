// The client's tile service over glintd against peers that break the
// protocol: every server message is checked before use, and a bad one loses
// that server with a reason that names it, never a crash or a wrong image.
#include "client/farm/distributed_tile_service.h"

#include <atomic>

#include <gtest/gtest.h>

#include "common/base/build_identity.h"
#include "common/base/error.h"
#include "proto/messages.h"
#include "tests/support/hostile_frames.h"
#include "tests/support/loopback_peer.h"

namespace glint {
namespace {

using proto::test::Peer;
using proto::test::readFrame;

const proto::SceneBundle kBundle{"{}", {}};

FrameSettings smallFrame() {
  FrameSettings f;
  f.width = 16;
  f.height = 8;
  return f;
}

// Two 8x8 tiles, every pixel traced.
std::vector<TileJob> twoTiles() { return {{{0, 0, 8, 8}, {}}, {{8, 0, 8, 8}, {}}}; }

void send(asio::ip::tcp::socket& socket, const std::vector<std::uint8_t>& frame) {
  asio::error_code ignored;
  asio::write(socket, asio::buffer(frame), ignored);
}

// A server that greets, holds the scene, reads the frame's setup and its two
// tile requests, then answers with `results` and waits for the client to go.
Peer scriptedServer(std::vector<std::vector<std::uint8_t>> results) {
  return Peer([results](asio::ip::tcp::socket& socket) {
    readFrame(socket);  // Hello
    send(socket, proto::encodeHello(1 << 20, 1, "fake"));
    readFrame(socket);  // SceneQuery
    send(socket, proto::encodeSceneStatus(kBundle.hash(), true));
    for (int i = 0; i < 3; ++i) readFrame(socket);  // FrameSetup, two TileRequests
    for (const auto& r : results) send(socket, r);
    while (!readFrame(socket).empty()) {
    }
  });
}

std::string addressOf(const Peer& peer) {
  return peer.endpoint().address().to_string() + ":" + std::to_string(peer.endpoint().port());
}

DistributedSettings quick() {
  DistributedSettings s;
  s.timeouts.connect = std::chrono::seconds(3);
  return s;
}

std::string renderError(Peer& peer) {
  DistributedTileService service(resolveServers({addressOf(peer)}), kBundle, quick());
  int calls = 0;
  try {
    service.render(smallFrame(), twoTiles(), [&](std::size_t, TileOutput&&) { ++calls; });
  } catch (const InputError& e) {
    EXPECT_LE(calls, 1);
    return e.what();
  }
  return "(no error)";
}

std::vector<std::uint8_t> pixels(std::size_t n) { return std::vector<std::uint8_t>(n, 7); }

TEST(DistributedTileService, ResultWithTheWrongNumberOfPixelsIsRefused) {
  Peer peer = scriptedServer({proto::encodeTileResult(1, 0, pixels(5), {}, 0)});
  const std::string error = renderError(peer);
  EXPECT_NE(error.find("lost, sent tile 0 of frame 1 with 5 bytes of pixels, not 192"), std::string::npos) << error;
}

TEST(DistributedTileService, SecondResultForATileIsRefused) {
  const auto first = proto::encodeTileResult(1, 0, pixels(192), {}, 0);
  Peer peer = scriptedServer({first, first});
  const std::string error = renderError(peer);
  EXPECT_NE(error.find("sent tile 0 of frame 1, which was not asked of it (or came twice)"), std::string::npos)
      << error;
}

TEST(DistributedTileService, ResultForATileNeverRequestedIsRefused) {
  Peer peer = scriptedServer({proto::encodeTileResult(1, 9, pixels(192), {}, 0)});
  const std::string error = renderError(peer);
  EXPECT_NE(error.find("sent tile 9 of frame 1, which was not asked of it"), std::string::npos) << error;
}

TEST(DistributedTileService, ResultWithoutABodyIsRefused) {
  Peer peer = scriptedServer({proto::test::bodylessFrame(wire::Body::TileResult)});
  const std::string error = renderError(peer);
  EXPECT_NE(error.find("carries none"), std::string::npos) << error;
}

TEST(DistributedTileService, HelloWithoutABodyIsRefused) {
  Peer peer([](asio::ip::tcp::socket& socket) {
    readFrame(socket);
    send(socket, proto::test::bodylessFrame(wire::Body::Hello));
    while (!readFrame(socket).empty()) {
    }
  });
  const std::string address = addressOf(peer);
  try {
    DistributedTileService service(resolveServers({address}), kBundle, quick());
    FAIL() << "a bodyless Hello was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("server " + address + ": unreachable, sent a bad message"),
              std::string::npos)
        << e.what();
  }
}

// A server that asks for a scene's files sends the client nothing it cannot
// bound: asking for one file a thousand times gets it once, and asking for
// a file the scene does not have loses the server, named.
TEST(DistributedTileService, FilesAskedForTwiceAreSentOnceAndUnknownOnesRefused) {
  const proto::SceneBundle bundle{"{}", {{"mesh.obj", std::string(5000, 'v')}}};
  for (const bool unknown : {false, true}) {
    std::atomic<int> chunks{0};
    Peer peer([&](asio::ip::tcp::socket& socket) {
      readFrame(socket);  // Hello
      send(socket, proto::encodeHello(1 << 20, 1, "fake"));
      readFrame(socket);  // SceneQuery
      std::vector<std::uint32_t> missing(1000, 0);
      if (unknown) missing.push_back(7);
      send(socket, proto::encodeSceneStatus(bundle.hash(), false, missing));
      for (std::vector<std::uint8_t> frame = readFrame(socket); !frame.empty(); frame = readFrame(socket)) {
        const wire::Body type = flatbuffers::GetRoot<wire::Message>(frame.data())->body_type();  // our client's
        if (type == wire::Body::FileChunk) ++chunks;
        if (type == wire::Body::SceneUpload) send(socket, proto::encodeSceneReady(bundle.hash(), 1.0f));
      }
    });
    const std::string address = addressOf(peer);
    try {
      DistributedTileService service(resolveServers({address}), bundle, quick());
      EXPECT_FALSE(unknown) << "a server asking for file 7 of 1 was taken";
    } catch (const InputError& e) {
      EXPECT_TRUE(unknown) << e.what();
      EXPECT_NE(std::string(e.what()).find("asked for file 7 of a scene of 1 files"), std::string::npos) << e.what();
    }
    if (!unknown) {
      EXPECT_EQ(chunks.load(), 1);  // counted before SceneReady went out
    }
  }
}

// A server whose pixels would differ (another build) is refused at Hello,
// with both builds named, rather than risk seams in the frame.
TEST(DistributedTileService, ServerOfAnotherBuildIsRefused) {
  Peer peer([](asio::ip::tcp::socket& socket) {
    readFrame(socket);
    send(socket, proto::encodeHello(1 << 20, 1, "fake", "pixels-0 some-other-compiler 0123"));
    while (!readFrame(socket).empty()) {
    }
  });
  try {
    DistributedTileService service(resolveServers({addressOf(peer)}), kBundle, quick());
    FAIL() << "a server of another build was taken";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unreachable, its pixels would differ"), std::string::npos) << what;
    EXPECT_NE(what.find("pixels-0 some-other-compiler 0123"), std::string::npos) << what;
    EXPECT_NE(what.find(buildIdentity()), std::string::npos) << what;
  }
}

// A server's Error text reaches the user cut to a few thousand bytes, its
// control characters (a terminal's escape sequences, newlines) written out:
// a 60 MB message once went to stderr whole, escapes and all.
TEST(DistributedTileService, ServerErrorTextIsBoundedAndEscaped) {
  const std::string message = "bad\x1b[2J\nforged line" + std::string(60'000'000, 'x');
  Peer peer([message](asio::ip::tcp::socket& socket) {
    readFrame(socket);  // Hello
    send(socket, proto::encodeError(wire::ErrorCode::Internal, message));
    while (!readFrame(socket).empty()) {
    }
  });
  try {
    DistributedTileService service(resolveServers({addressOf(peer)}), kBundle, quick());
    FAIL() << "a server that answered Hello with an Error was taken";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad\\x1b[2J\\nforged line"), std::string::npos) << what.substr(0, 300);
    EXPECT_EQ(what.find('\x1b'), std::string::npos);
    EXPECT_EQ(what.find("\nforged"), std::string::npos);
    EXPECT_LT(what.size(), 4000u);
    EXPECT_NE(what.find("more bytes)"), std::string::npos);
  }
}

// A server that lacks the scene, takes the upload and never says it holds
// it is given up after --scene-timeout (counted from the upload's last
// piece), named, not after a fixed five minutes.
TEST(DistributedTileService, ServerThatNeverConfirmsTheSceneTimesOut) {
  Peer peer([](asio::ip::tcp::socket& socket) {
    readFrame(socket);  // Hello
    send(socket, proto::encodeHello(1 << 20, 1, "fake"));
    readFrame(socket);  // SceneQuery
    send(socket, proto::encodeSceneStatus(kBundle.hash(), false));
    while (!readFrame(socket).empty()) {
    }
  });
  DistributedSettings settings = quick();
  settings.timeouts.scene = std::chrono::seconds(1);
  const auto start = std::chrono::steady_clock::now();
  try {
    DistributedTileService service(resolveServers({addressOf(peer)}), kBundle, settings);
    FAIL() << "a server that never confirmed the scene was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no answer within 1 s (scene upload and build; --scene-timeout)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

}  // namespace
}  // namespace glint
