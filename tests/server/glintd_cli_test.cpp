// glintd's command line as a user meets it: a usage error is one line that
// says what is wrong and exits with 2; the line scripts wait for says how
// clients reach it.
#include <csignal>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/glint_run.h"
#include "tests/support/glintd_process.h"

namespace glint::test {
namespace {

bool oneUsageLine(const GlintRun& r) {
  return r.status == 2 && r.output.rfind("glintd: error: ", 0) == 0 && r.output.find('\n') == r.output.size() - 1 &&
         r.output.find("(the options: glintd --help)") != std::string::npos;
}

TEST(GlintdCli, AnAddressItCannotListenOnIsAUsageError) {
  const GlintRun port = runGlintd("--listen 127.0.0.1:99999");
  EXPECT_TRUE(oneUsageLine(port)) << port.status << ": " << port.output;
  EXPECT_NE(port.output.find("--listen: 127.0.0.1:99999: the port must be in [0, 65535]"), std::string::npos)
      << port.output;
  const GlintRun host = runGlintd("--listen nowhere");
  EXPECT_TRUE(oneUsageLine(host)) << host.status << ": " << host.output;
}

TEST(GlintdCli, AMisspeltOptionNamesTheNearestOne) {
  const GlintRun run = runGlintd("--lisen 127.0.0.1:0");
  EXPECT_EQ(run.output,
            "glintd: error: glintd has no option --lisen; did you mean --listen? (the options: glintd --help)\n");
  EXPECT_EQ(run.status, 2);
  const GlintRun far = runGlintd("--colour red");
  EXPECT_TRUE(oneUsageLine(far)) << far.status << ": " << far.output;
  EXPECT_EQ(far.output.find("did you mean"), std::string::npos) << far.output;
}

// Options that do not go together are usage errors too, found before any
// socket is opened.
TEST(GlintdCli, OptionsThatDoNotGoTogetherAreUsageErrors) {
  for (const char* args : {"--listen 127.0.0.1:0 --max-scene-mb 300 --cache-mb 100",
                           "--listen 127.0.0.1:0 --cache-mb 100 --max-scene-mb 50 --max-memory-mb 150",
                           "--listen 127.0.0.1:0 --tls-cert c.pem", "--listen 0.0.0.0:0"}) {
    const GlintRun run = runGlintd(args);
    EXPECT_TRUE(oneUsageLine(run)) << args << " -> " << run.status << ": " << run.output;
  }
}

TEST(GlintdCli, TheListeningLineSaysTheThreadsAndWhetherTlsIsOn) {
  const server::test::GlintdProcess one({"--threads", "1"});
  EXPECT_NE(one.listeningLine().find(", 1 thread, no TLS"), std::string::npos) << one.listeningLine();
  const server::test::GlintdProcess two({"--threads", "2"});
  EXPECT_NE(two.listeningLine().find(", 2 threads, no TLS"), std::string::npos) << two.listeningLine();
}

// --quiet prints nothing while serving a client and stopping, not even the
// listening line; --ready-fd gives that line to whoever asked for it.
TEST(GlintdCli, QuietPrintsNothingAndTheReadyDescriptorSaysWhereItListens) {
  server::test::GlintdProcess quiet;
  EXPECT_EQ(quiet.listeningLine().rfind("glintd: listening on 127.0.0.1:", 0), 0u) << quiet.listeningLine();
  const std::string out = ::testing::TempDir() + "quiet-served.png";
  const GlintRun served = runGlint("render " + std::string(GLINT_SOURCE_DIR) + "/scenes/room.json --size 32x24 -q -o " + out +
                                   " --server " + quiet.address());
  EXPECT_EQ(served.status, 0) << served.output;
  EXPECT_EQ(quiet.stop(SIGTERM), 0);
  EXPECT_EQ(quiet.printed(), "");
}

TEST(GlintdCli, AReadyDescriptorThatIsNotOpenIsAUsageError) {
  const GlintRun run = runGlintd("--listen 127.0.0.1:0 --ready-fd 9 9<&-");
  EXPECT_TRUE(oneUsageLine(run)) << run.status << ": " << run.output;
  EXPECT_NE(run.output.find("--ready-fd 9: not a descriptor open for writing"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace glint::test
