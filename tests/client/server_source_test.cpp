// Where the farm's servers come from: a --server-file read again when its
// text changes, names resolved again every few seconds, and what cannot be
// used keeping the farm as it was, said once.
#include "client/farm/server_source.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "common/base/error.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using Clock = ServerSource::Clock;

class ServerSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("glint_server_source_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file() const { return (dir_ / "servers.txt").string(); }
  void write(const std::string& text) const { std::ofstream(file()) << text; }

  fs::path dir_;
};

std::vector<std::string> names(const ServerSource& source) {
  std::vector<std::string> out;
  for (const ServerAddress& a : source.addresses()) out.push_back(a.name);
  return out;
}

TEST_F(ServerSourceTest, ReadsTheFileBesidesTheOptionWithCommentsAndBlankLines) {
  write("# the farm\n127.0.0.1:7001\n\n  127.0.0.1:7002   # second rack\n\t\n");
  const ServerSource source({"127.0.0.1:7000"}, file(), Clock::now());
  EXPECT_EQ(names(source), (std::vector<std::string>{"127.0.0.1:7000", "127.0.0.1:7001", "127.0.0.1:7002"}));
}

TEST_F(ServerSourceTest, AChangedFileChangesTheSetAtTheNextRefresh) {
  write("127.0.0.1:7001\n127.0.0.1:7002\n");
  const Clock::time_point start = Clock::now();
  ServerSource source({}, file(), start);
  EXPECT_FALSE(source.refresh(start));  // nothing changed
  write("127.0.0.1:7001\n127.0.0.1:7003\n");
  EXPECT_TRUE(source.refresh(start));
  EXPECT_EQ(names(source), (std::vector<std::string>{"127.0.0.1:7001", "127.0.0.1:7003"}));
  write("127.0.0.1:7003\n127.0.0.1:7001   # the same servers, another order and a comment\n");
  EXPECT_FALSE(source.refresh(start));
  EXPECT_EQ(source.warning(), "");
}

TEST_F(ServerSourceTest, WhatCannotBeUsedAtTheStartIsAnErrorNamingTheLine) {
  write("127.0.0.1:7001\nnot-a-server\n");
  try {
    ServerSource source({}, file(), Clock::now());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--server-file " + file() + ":2 not-a-server: expected HOST:PORT"),
              std::string::npos)
        << e.what();
  }
  write("# nobody yet\n");
  EXPECT_THROW(ServerSource({}, file(), Clock::now()), InputError);
  EXPECT_THROW(ServerSource({}, (dir_ / "missing.txt").string(), Clock::now()), InputError);
}

TEST_F(ServerSourceTest, WhatCannotBeUsedLaterKeepsTheFarmAndSaysWhy) {
  write("127.0.0.1:7001\n");
  const Clock::time_point start = Clock::now();
  ServerSource source({}, file(), start);
  write("127.0.0.1:7001\n127.0.0.1:99999\n");
  EXPECT_FALSE(source.refresh(start));
  EXPECT_NE(source.warning().find(":2 127.0.0.1:99999: expected HOST:PORT"), std::string::npos) << source.warning();
  EXPECT_NE(source.warning().find("the farm stays as it was (1 server)"), std::string::npos) << source.warning();
  write("");  // half written, or emptied by mistake: a farm of none is never taken
  EXPECT_FALSE(source.refresh(start));
  EXPECT_NE(source.warning().find("lists no server"), std::string::npos) << source.warning();
  fs::remove(file());
  EXPECT_FALSE(source.refresh(start));
  EXPECT_NE(source.warning().find("cannot be read"), std::string::npos) << source.warning();
  EXPECT_EQ(names(source), (std::vector<std::string>{"127.0.0.1:7001"}));
  write("127.0.0.1:7002\n");  // fixed: taken, and the warning is gone
  EXPECT_TRUE(source.refresh(start));
  EXPECT_EQ(names(source), (std::vector<std::string>{"127.0.0.1:7002"}));
  EXPECT_EQ(source.warning(), "");
}

// A name's addresses as a DNS server would give them over time (a headless
// Service scaling from two pods to three, then to one).
TEST_F(ServerSourceTest, NamesAreResolvedAgainEveryFewSeconds) {
  std::vector<std::string> pods{"10.0.0.1", "10.0.0.2"};
  int lookups = 0;
  const ServerSource::Resolve dns = [&](const std::vector<ServerEntry>& entries) {
    ++lookups;
    EXPECT_EQ(entries.size(), 1u);
    EXPECT_EQ(entries[0].value, "glintd.farm:7878");
    std::vector<ServerAddress> out;
    for (const std::string& ip : pods) {
      out.push_back({"glintd.farm:7878 (" + ip + ")", "glintd.farm", {asio::ip::make_address(ip), 7878}});
    }
    return out;
  };
  const Clock::time_point start = Clock::now();
  ServerSource source({"glintd.farm:7878"}, "", start, dns);
  EXPECT_EQ(source.addresses().size(), 2u);
  pods.push_back("10.0.0.3");
  EXPECT_FALSE(source.refresh(start + ServerSource::kResolveEvery / 2));  // not yet asked again
  EXPECT_EQ(lookups, 1);
  EXPECT_TRUE(source.refresh(start + ServerSource::kResolveEvery));
  EXPECT_EQ(source.addresses().size(), 3u);
  pods = {"10.0.0.2"};
  EXPECT_TRUE(source.refresh(start + 2 * ServerSource::kResolveEvery));
  EXPECT_EQ(names(source), (std::vector<std::string>{"glintd.farm:7878 (10.0.0.2)"}));
  EXPECT_EQ(lookups, 3);
}

TEST_F(ServerSourceTest, AFixedListNeverChanges) {
  ServerSource source(std::vector<ServerAddress>{{"a:1", "a", {asio::ip::make_address("127.0.0.1"), 1}}});
  EXPECT_FALSE(source.refresh(Clock::now() + std::chrono::hours(1)));
  EXPECT_EQ(source.addresses().size(), 1u);
}

}  // namespace
}  // namespace glint
