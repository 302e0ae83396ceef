// One frame over several real glintd processes on loopback: byte-identical to
// the in-process frame whatever happens to the servers (killed mid-frame,
// stopped, speaking garbage, unreachable), with the stats naming who was
// lost and which tiles were re-issued.
#include <signal.h>

#include <filesystem>
#include <thread>

#include <gtest/gtest.h>

#include "client/farm/distributed_tile_service.h"
#include "client/raster/hybrid_frame.h"
#include "client/raster/offscreen_context.h"
#include "client/raster/raster_scene.h"
#include "client/commands/render_command.h"
#include "common/base/error.h"
#include "common/render/field_probes.h"
#include "common/render/frame.h"
#include "proto/messages.h"
#include "tests/support/test_support.h"
#include "tests/support/loopback_peer.h"
#include "tests/support/glintd_process.h"
#include "tests/support/message_stream.h"

namespace glint {
namespace {

using server::test::GlintdProcess;

struct Room {
  proto::LoadedBundle loaded = proto::loadSceneBundle(test::sourcePath("scenes/room.json"));
  FrameSettings frame = [this] {
    FrameSettings f = loaded.scene.frame;
    f.width = 160;
    f.height = 120;
    return f;
  }();
};

FrameOptions smallTiles() {
  FrameOptions o;
  o.tileSize = 8;  // 300 tiles: every server holds some when one is lost
  return o;
}

FrameImage inProcess(const Room& room) {
  const PreparedScene prepared(room.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService service(prepared, pool);
  return renderFrame(service, room.frame, smallTiles()).image;
}

// Three single-threaded glintd, started in the constructor.
struct Farm {
  GlintdProcess a{{"--threads", "1"}}, b{{"--threads", "1"}}, c{{"--threads", "1"}};
  std::vector<std::string> addresses() const { return {a.address(), b.address(), c.address()}; }
};

DistributedSettings stallAfter(std::chrono::milliseconds ms) {
  DistributedSettings s;
  s.stallTimeout = ms;
  return s;
}

TEST(ManyServers, ThreeServersGiveTheInProcessFrameAndAllTakePart) {
  const Room room;
  Farm farm;
  DistributedTileService service(resolveServers(farm.addresses()), room.loaded.bundle);
  service.awaitServers(std::chrono::seconds(10));
  EXPECT_EQ(renderFrame(service, room.frame, smallTiles()).image.rgb, inProcess(room).rgb);
  for (const ServerReport& s : service.lastFrame().servers) {
    EXPECT_EQ(s.state, ServerState::kOk) << s.address;
    EXPECT_GT(s.tiles, 0u) << s.address;
  }
  // The hybrid frame (--mask auto) too.
  const PreparedScene prepared(room.loaded.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  gl::OffscreenContext context(room.frame.width, room.frame.height);
  gl::RasterScene raster(context.api(), prepared.scene());
  HybridResult here, there;
  renderHybrid(context.api(), raster, local, room.frame, prepared.scene().mask, 16, here);
  renderHybrid(context.api(), raster, service, room.frame, prepared.scene().mask, 16, there);
  EXPECT_GT(here.maskedPixels, 1000u);
  EXPECT_EQ(there.image.rgb, here.image.rgb);
}

// Path transport through glintd: the FrameSetup carries the transport and
// the bounces, and every random number comes from the sample's key, so the
// servers' tiles are the in-process frame's bytes.
TEST(ManyServers, APathTracedFrameIsTheInProcessFrame) {
  const proto::LoadedBundle cornell = proto::loadSceneBundle(test::sourcePath("scenes/cornell.json"));
  FrameSettings frame = cornell.scene.frame;
  frame.width = 64;
  frame.height = 64;
  frame.sampling.samples = 4;
  const PreparedScene prepared(cornell.scene, BvhSettings{});
  ThreadPool pool(2);
  LocalTileService local(prepared, pool);
  const FrameImage here = renderFrame(local, frame, smallTiles()).image;
  Farm farm;
  DistributedTileService service(resolveServers(farm.addresses()), cornell.bundle);
  service.awaitServers(std::chrono::seconds(10));
  EXPECT_EQ(renderFrame(service, frame, smallTiles()).image.rgb, here.rgb);
  frame.tracing.maxBounces = 1;  // and a setting that changes the light reaches them
  const FrameImage oneBounce = renderFrame(service, frame, smallTiles()).image;
  EXPECT_NE(oneBounce.rgb, here.rgb);
  EXPECT_EQ(oneBounce.rgb, renderFrame(local, frame, smallTiles()).image.rgb);
}

// Server a is stopped before the frame, so that it holds the tiles it is
// given, and killed once the frame is under way: its connection closes with
// tiles outstanding, which the others take.
TEST(ManyServers, AServerKilledMidFrameIsReplacedByTheOthers) {
  const Room room;
  const FrameImage expected = inProcess(room);
  Farm farm;
  DistributedTileService service(resolveServers(farm.addresses()), room.loaded.bundle);
  service.awaitServers(std::chrono::seconds(10));
  ::kill(farm.a.pid(), SIGSTOP);
  FrameOptions options = smallTiles();
  bool killed = false;
  options.progress = [&farm, &killed](int done, int) {  // pixels: five tiles of 8 x 8
    if (!killed && done >= 5 * 64) ::kill(farm.a.pid(), SIGKILL);
    killed = killed || done >= 5 * 64;
  };
  EXPECT_EQ(renderFrame(service, room.frame, options).image.rgb, expected.rgb);
  const DistributionReport& report = service.lastFrame();
  EXPECT_EQ(report.servers[0].state, ServerState::kLost);
  EXPECT_NE(report.servers[0].why.find("connection"), std::string::npos) << report.servers[0].why;
  EXPECT_GT(report.reissuedTiles, 0u);
  EXPECT_EQ(report.servers[0].tiles, 0u);
  // The next frame goes on without it (its retry fails: nothing listens).
  EXPECT_EQ(renderFrame(service, room.frame, smallTiles()).image.rgb, expected.rgb);
  EXPECT_EQ(service.lastFrame().servers[0].tiles, 0u);
}

// The field's probes, as the wire carries them.
std::vector<float> probeFloats(const IrradianceField& field) {
  constexpr std::size_t n = IrradianceField::kProbeFloats;
  std::vector<float> out(static_cast<std::size_t>(field.probeCount()) * n);
  for (int i = 0; i < field.probeCount(); ++i) {
    IrradianceField::writeProbe(field.probe(i), std::span<float, n>(out.data() + static_cast<std::size_t>(i) * n, n));
  }
  return out;
}

// Server a is stopped before the irradiance field's fill, so that it holds
// the batches it is given, and killed once two batches are in: the others
// trace its batches, and the field is the in-process one's bytes.
TEST(ManyServers, AServerKilledMidFillLeavesItsBatchesToTheOthers) {
  const proto::LoadedBundle cornell = proto::loadSceneBundle(test::sourcePath("scenes/cornell.json"));
  const FrameSettings& frame = cornell.scene.frame;
  const FieldSettings settings{8, 64};
  const PreparedScene prepared(cornell.scene, BvhSettings{});
  RayStats rays;
  const IrradianceField here = buildField(prepared, frame, settings, rays);
  ASSERT_GT(here.probeCount(), 4 * DistributedTileService::kBatchProbes);
  Farm farm;
  DistributedTileService service(resolveServers(farm.addresses()), cornell.bundle);
  service.awaitServers(std::chrono::seconds(10));
  ::kill(farm.a.pid(), SIGSTOP);
  bool killed = false;
  service.onTraced([&farm, &killed](std::size_t probes) {
    if (!killed && probes >= 2 * DistributedTileService::kBatchProbes) ::kill(farm.a.pid(), SIGKILL);
    killed = killed || probes >= 2 * DistributedTileService::kBatchProbes;
  });
  const IrradianceField there = service.fillField(frame, cornell.scene.geometry.bounds(), settings);
  EXPECT_EQ(probeFloats(there), probeFloats(here));
  const DistributionReport& report = service.fieldReport();
  EXPECT_EQ(report.servers[0].state, ServerState::kLost);
  EXPECT_GT(report.reissuedTiles, 0u);
  EXPECT_EQ(report.servers[0].tiles, 0u);
  EXPECT_EQ(report.servers[1].probes + report.servers[2].probes, static_cast<std::size_t>(here.probeCount()));
}

// A fake server's greeting: Hello back, and the room's scene held.
void greetHoldingTheRoom(asio::ip::tcp::socket& socket, const char* software) {
  proto::test::readFrame(socket);  // Hello
  proto::test::writeFrame(socket, proto::encodeHello(1 << 20, 1, software));
  proto::test::readFrame(socket);  // SceneQuery
  proto::test::writeFrame(socket, proto::encodeSceneStatus(Room().loaded.bundle.hash(), true));
}

// A server that answers its first tiles with pixels of its own making and
// is then caught sending one of them twice is lost for breaking the
// protocol, and the tiles it had delivered are traced again by the others:
// the frame is the in-process one (its white tiles used to stay in it).
TEST(ManyServers, TilesOfAServerCaughtLyingAreTracedAgainElsewhere) {
  const Room room;
  GlintdProcess honest({"--threads", "1"});
  proto::test::Peer liar([&room](asio::ip::tcp::socket& socket) {
    const auto send = [&socket](const std::vector<std::uint8_t>& frame) { proto::test::writeFrame(socket, frame); };
    greetHoldingTheRoom(socket, "liar");
    std::vector<std::uint8_t> first;
    int answered = 0;
    for (auto bytes = proto::test::readFrame(socket); !bytes.empty(); bytes = proto::test::readFrame(socket)) {
      const auto* request = flatbuffers::GetRoot<wire::Message>(bytes.data())->body_as_TileRequest();
      if (!request || answered == 3) continue;
      const std::vector<std::uint8_t> white(std::size_t{request->width()} * request->height() * 3, 255);
      const auto lie = proto::encodeTileResult(request->frame_id(), request->tile_id(), white, {}, 0);
      if (first.empty()) first = lie;
      send(lie);
      if (++answered == 3) send(first);
    }
  });
  const std::string liarAddress =
      liar.endpoint().address().to_string() + ":" + std::to_string(liar.endpoint().port());
  DistributedTileService service(resolveServers({liarAddress, honest.address()}), room.loaded.bundle);
  service.awaitServers(std::chrono::seconds(10));
  EXPECT_EQ(renderFrame(service, room.frame, smallTiles()).image.rgb, inProcess(room).rgb);
  const DistributionReport& report = service.lastFrame();
  EXPECT_EQ(report.servers[0].state, ServerState::kLost);
  EXPECT_NE(report.servers[0].why.find("came twice"), std::string::npos) << report.servers[0].why;
  EXPECT_EQ(report.servers[0].tiles, 0u);
  EXPECT_GE(report.reissuedTiles, 3u);
}

// A stopped server holds its tiles without a word; once the stall timeout
// passes (the frame is long enough: 4800 tiles) they go to the others. Woken
// again, it is taken back after its backoff (1 s): its link is made again at
// the start of a frame and joins that frame once it is ready, so on a busy
// machine (the woken glintd first finishes the tiles it held) it may take a
// few frames.
TEST(ManyServers, AStoppedServerStallsAndItsTilesGoElsewhere) {
  Room room;
  room.frame.width = 640;
  room.frame.height = 480;
  Farm farm;
  DistributedTileService service(resolveServers(farm.addresses()), room.loaded.bundle,
                                 stallAfter(std::chrono::milliseconds(60)));
  service.awaitServers(std::chrono::seconds(10));
  ::kill(farm.b.pid(), SIGSTOP);
  const FrameImage image = renderFrame(service, room.frame, smallTiles()).image;
  ::kill(farm.b.pid(), SIGCONT);
  EXPECT_EQ(image.rgb, inProcess(room).rgb);
  const ServerReport& stopped = service.lastFrame().servers[1];
  EXPECT_EQ(stopped.state, ServerState::kLost);
  EXPECT_NE(stopped.why.find("stalled"), std::string::npos) << stopped.why;
  EXPECT_GT(service.lastFrame().reissuedTiles, 0u);

  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  for (int frame = 0; frame == 0 || (frame < 5 && service.lastFrame().servers[1].tiles == 0); ++frame) {
    EXPECT_EQ(renderFrame(service, room.frame, smallTiles()).image.rgb, image.rgb);
  }
  const ServerReport& back = service.lastFrame().servers[1];
  EXPECT_EQ(back.state, ServerState::kOk) << back.why;
  EXPECT_GT(back.tiles, 0u);
}

// A peer that greets properly, claims the scene, and answers its first tile
// request with bytes that are no Glint message.
proto::test::Peer garbageServer() {
  return proto::test::Peer([](asio::ip::tcp::socket& socket) {
    const auto send = [&socket](const std::vector<std::uint8_t>& bytes) { proto::test::writeFrame(socket, bytes); };
    greetHoldingTheRoom(socket, "garbage");
    proto::test::readFrame(socket);  // FrameSetup
    proto::test::readFrame(socket);  // a TileRequest
    send({13, 0, 0, 0, 'n', 'o', 't', ' ', 'a', ' ', 'm', 'e', 's', 's', 'a', 'g', 'e'});
    while (!proto::test::readFrame(socket).empty()) {
    }
  });
}

TEST(ManyServers, GarbageAndAnUnreachableAddressAmongGoodServers) {
  const Room room;
  GlintdProcess good({"--threads", "1"});
  proto::test::Peer garbage = garbageServer();
  const std::string garbageAddress = "127.0.0.1:" + std::to_string(garbage.endpoint().port());
  DistributedTileService service(resolveServers({good.address() + "," + garbageAddress, "127.0.0.1:1"}),
                                 room.loaded.bundle);
  service.awaitServers(std::chrono::seconds(10));
  EXPECT_EQ(renderFrame(service, room.frame, smallTiles()).image.rgb, inProcess(room).rgb);
  const DistributionReport& report = service.lastFrame();
  ASSERT_EQ(report.servers.size(), 3u);
  EXPECT_EQ(report.servers[0].state, ServerState::kOk);
  EXPECT_EQ(report.servers[1].state, ServerState::kLost);
  EXPECT_NE(report.servers[1].why.find("bad message"), std::string::npos) << report.servers[1].why;
  EXPECT_EQ(report.servers[2].state, ServerState::kUnreachable);
  EXPECT_NE(report.servers[2].why.find("cannot connect"), std::string::npos) << report.servers[2].why;
}

// A scene every server refuses (here: over their --max-scene-mb) fails the
// render with the server's message naming the place, not as lost servers.
TEST(ManyServers, ASceneErrorFailsTheRenderWithItsPlace) {
  const std::vector<std::string> small{"--max-scene-mb", "56", "--cache-mb", "64", "--max-memory-mb", "256"};
  GlintdProcess a(small), b(small);
  const proto::SceneBundle bundle{R"({"glint": 1, "image": {"width": 4, "height": 4},
      "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
      "textures": {"a": {"type": "image", "file": "a.png"}, "b": {"type": "image", "file": "b.png"},
                   "c": {"type": "image", "file": "c.png"}},
      "materials": {"m": {"texture": "a"}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})",
                                  {{"a.png", test::flatPng(2048, 2048)},  // 12 MiB of texels each
                                   {"b.png", test::flatPng(2048, 2048)},
                                   {"c.png", test::flatPng(2048, 2048)}}};
  try {
    DistributedTileService service(resolveServers({a.address(), b.address()}), bundle);
    FAIL() << "a scene over the servers' limit was taken";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(": BadScene: textures.c.file: the scene would hold 60.0 MiB while it decodes"),
              std::string::npos)
        << what;
    EXPECT_EQ(what.find("no glintd can serve"), std::string::npos) << what;
  }
}

// No server at all: the error names each one and why, and no file is written.
// A glintd full of clients answers Busy; its idle client's place is given
// to a newcomer a second later. The frame waits for it (a retry with
// backoff within the scene timeout) instead of failing at once.
TEST(ManyServers, ABusyServerIsTriedAgainAndServesTheFrame) {
  GlintdProcess glintd({"--max-clients", "1", "--threads", "1"});
  proto::MessageStream idle({asio::ip::make_address("127.0.0.1"), glintd.port()}, std::chrono::seconds(3));
  idle.send(proto::encodeHello(1 << 20, 0, "idle"));
  ASSERT_NE(idle.receive().body_as_Hello(), nullptr);
  const std::string out = (std::filesystem::temp_directory_path() / "glint-busy-server.png").string();
  RenderOptions options;
  options.scene = test::sourcePath("scenes/room.json");
  options.output = out;
  options.frame.mask = MaskRule::kAll;
  options.frame.width = 80;
  options.frame.height = 60;
  options.remote.servers = {glintd.address()};
  options.quiet = true;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_NO_THROW(runRender(options));
  EXPECT_TRUE(std::filesystem::exists(out));
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(900));
  std::filesystem::remove(out);
}

TEST(ManyServers, EveryServerUnreachableWritesNothing) {
  const std::string out = (std::filesystem::temp_directory_path() / "glint-no-servers.png").string();
  std::filesystem::remove(out);
  RenderOptions options;
  options.scene = test::sourcePath("scenes/room.json");
  options.output = out;
  options.frame.mask = MaskRule::kAll;
  options.remote.servers = {"127.0.0.1:1,127.0.0.1:2", "127.0.0.1:1"};
  options.quiet = true;
  try {
    runRender(options);
    FAIL() << "rendered without a server";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("server 127.0.0.1:1: unreachable, cannot connect"), std::string::npos) << what;
    EXPECT_NE(what.find("server 127.0.0.1:2: unreachable, cannot connect"), std::string::npos) << what;
    EXPECT_EQ(what.find("127.0.0.1:1", what.find("127.0.0.1:2")), std::string::npos) << "merged: " << what;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace glint
