// --server values to servers: lists, repeats, names, duplicates merged, and
// clear errors for what cannot be a server.
#include "client/farm/server_list.h"

#include <gtest/gtest.h>

#include "common/base/error.h"

namespace glint {
namespace {

std::string errorOf(const std::vector<std::string>& values) {
  try {
    resolveServers(values);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ServerList, ListsAndRepeatsGiveOneServerPerAddressInOrder) {
  const auto servers = resolveServers({"127.0.0.1:7001,127.0.0.2:7002", "[::1]:7003", "localhost:7004"});
  ASSERT_EQ(servers.size(), 4u);
  EXPECT_EQ(servers[0].name, "127.0.0.1:7001");
  EXPECT_EQ(servers[1].endpoint, asio::ip::tcp::endpoint(asio::ip::make_address("127.0.0.2"), 7002));
  EXPECT_EQ(servers[2].endpoint, asio::ip::tcp::endpoint(asio::ip::make_address("::1"), 7003));
  // localhost is its IPv4 address only: one server, not also a ::1 that glintd may not listen on.
  EXPECT_EQ(servers[3].endpoint, asio::ip::tcp::endpoint(asio::ip::make_address("127.0.0.1"), 7004));
  EXPECT_EQ(servers[3].name, "localhost:7004");
}

TEST(ServerList, DuplicatesAreMerged) {
  const auto servers = resolveServers({"127.0.0.1:7001,localhost:7001", "127.0.0.1:7001,,127.0.0.1:7002"});
  ASSERT_EQ(servers.size(), 2u);
  EXPECT_EQ(servers[0].name, "127.0.0.1:7001");
  EXPECT_EQ(servers[1].name, "127.0.0.1:7002");
}

TEST(ServerList, WhatCannotBeAServerIsNamed) {
  EXPECT_NE(errorOf({"nowhere"}).find("--server nowhere: expected HOST:PORT"), std::string::npos);
  EXPECT_NE(errorOf({"127.0.0.1:70000"}).find("--server 127.0.0.1:70000: expected HOST:PORT"), std::string::npos);
  EXPECT_NE(errorOf({"127.0.0.1:"}).find("expected HOST:PORT"), std::string::npos);
  EXPECT_NE(errorOf({"no-such-host.invalid:7878"}).find("--server no-such-host.invalid:7878: cannot resolve"),
            std::string::npos)
      << errorOf({"no-such-host.invalid:7878"});
  EXPECT_NE(errorOf({","}).find("--server: no address given"), std::string::npos);
}

// A server file's lines reach the terminal in the warnings only escaped:
// an ESC sequence in a line cannot recolour or rewrite the user's terminal.
TEST(ServerList, ALinesControlBytesAreEscapedInItsError) {
  const auto entries = parseServerFile("\x1b[2J\x1b[31mevil.invalid:7878\n", "farm.txt");
  ASSERT_EQ(entries.size(), 1u);
  std::string error = "(no error)";
  try {
    resolveEntries(entries);
  } catch (const InputError& e) {
    error = e.what();
  }
  EXPECT_EQ(error.find('\x1b'), std::string::npos) << error;
  EXPECT_NE(error.find("farm.txt:1 \\x1b[2J\\x1b[31mevil.invalid:7878: cannot resolve"), std::string::npos) << error;
  try {
    resolveEntries(parseServerFile("\x1b]0;title\x07:99999\n", "farm.txt"));
  } catch (const InputError& e) {
    error = e.what();
  }
  EXPECT_EQ(error.find('\x1b'), std::string::npos) << error;
  EXPECT_NE(error.find("\\x1b]0;title\\x07:99999: expected HOST:PORT"), std::string::npos) << error;
}

TEST(ServerList, AServerFileIsOneEntryALineNamedByItsLine) {
  const auto entries = parseServerFile("# farm\n\n a:1 \nb:2,c:3 # rack 2\r\n#d:4\n", "farm.txt");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].value, "a:1");
  EXPECT_EQ(entries[0].origin, "farm.txt:3");
  EXPECT_EQ(entries[1].value, "b:2,c:3");
  EXPECT_EQ(entries[1].origin, "farm.txt:4");
}

}  // namespace
}  // namespace glint
