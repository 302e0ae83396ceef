// A real glintd process against what an attacker on the network can send
// (issue 9): after each attack the process is still up, a normal client is
// still served, and the server's memory stays within a stated bound.
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "client/remote_tile_service.h"
#include "common/error.h"
#include "common/frame.h"
#include "proto/messages.h"
#include "server/log.h"
#include "tests/common/test_support.h"
#include "tests/proto/hostile_frames.h"
#include "tests/server/glintd_process.h"
#include "tests/server/raw_client.h"

namespace glint::server {
namespace {

using namespace std::chrono_literals;
using test::GlintdProcess;
using test::RawClient;

// A small frame of the thesis room through `address`; throws InputError.
FrameImage renderRoom(const std::string& address) {
  const proto::LoadedBundle loaded = proto::loadSceneBundle(glint::test::sourcePath("scenes/room.json"));
  FrameSettings frame = loaded.scene.frame();
  frame.width = 48;
  frame.height = 36;
  RemoteTileService service(address, loaded.bundle, 10s);
  return renderFrame(service, frame, {}).image;
}

// One frame for every body type, before Hello and after it: each is answered
// with an Error or a close, and glintd lives on. It used to dereference the
// missing body: one 28-byte frame ended the service for every client.
TEST(HostileClient, MessagesWithoutABodyDoNotCrashTheServer) {
  GlintdProcess glintd;
  for (const wire::Body type : proto::test::allBodyTypes()) {
    for (const bool greeted : {false, true}) {
      RawClient c(glintd.port());
      if (greeted) {
        ASSERT_TRUE(c.hello());
      }
      c.write(proto::test::bodylessFrame(type));
      const auto [code, text] = c.readError();
      EXPECT_EQ(code, wire::ErrorCode::Malformed) << wire::EnumNameBody(type) << ": " << text;
      EXPECT_TRUE(c.closed());
      ASSERT_TRUE(glintd.running()) << "glintd died on a bodyless " << wire::EnumNameBody(type);
    }
  }
  EXPECT_EQ(renderRoom(glintd.address()).width, 48);
}

}  // namespace
}  // namespace glint::server
