#include "server/connection_registry.h"

#include <vector>

#include <gtest/gtest.h>

namespace glint::server {
namespace {

using namespace std::chrono_literals;
using Clock = ConnectionRegistry::Clock;

struct FakeConnection : ConnectionHandle {
  void close(const std::string& why) override { closedWhy = why; }
  std::string closedWhy;
};

struct Pool {
  explicit Pool(std::size_t maxClients) : registry(maxClients, 16) {}
  // A connection that says Hello at `when`; whether it got a place.
  bool hello(std::uint64_t id, Clock::time_point when) {
    connections.resize(std::max<std::size_t>(connections.size(), id + 1));
    connections[id] = std::make_shared<FakeConnection>();
    registry.addWaiting(id, connections[id]);
    return registry.admit(id, when);
  }
  ConnectionRegistry registry;
  std::vector<std::shared_ptr<FakeConnection>> connections;
};

// Full of clients that just said Hello: a newcomer gets Busy, and no one is
// closed.
TEST(ConnectionRegistry, FullOfFreshClientsRefusesANewcomer) {
  const Clock::time_point t0 = Clock::now();
  Pool p(2);
  ASSERT_TRUE(p.hello(0, t0));
  ASSERT_TRUE(p.hello(1, t0 + 100ms));
  EXPECT_FALSE(p.hello(2, t0 + 900ms));
  EXPECT_EQ(p.registry.clients(), 2u);
  EXPECT_TRUE(p.connections[0]->closedWhy.empty());
}

// Full of clients idle for a second or more: the newcomer takes the place of
// the one that asked for work least recently, which is closed with why.
TEST(ConnectionRegistry, NewcomerTakesTheIdlestPlace) {
  const Clock::time_point t0 = Clock::now();
  Pool p(2);
  ASSERT_TRUE(p.hello(0, t0));
  ASSERT_TRUE(p.hello(1, t0 + 100ms));
  p.registry.worked(0, t0 + 1s);  // 0 works; 1 has only said Hello
  EXPECT_TRUE(p.hello(2, t0 + 1500ms));
  EXPECT_EQ(p.registry.clients(), 2u);
  EXPECT_TRUE(p.connections[0]->closedWhy.empty());
  EXPECT_EQ(p.connections[1]->closedWhy, "dropped: idle while a new client wanted its place");
  // Now 0 (work at 1 s) and 2 (Hello at 1.5 s): at 1.9 s neither is idle long enough.
  EXPECT_FALSE(p.hello(3, t0 + 1900ms));
  EXPECT_TRUE(p.hello(4, t0 + 2100ms));
  EXPECT_FALSE(p.connections[0]->closedWhy.empty());
}

}  // namespace
}  // namespace glint::server
