// glint and glintd over mutual TLS, with certificates made by
// deploy/glint-certs for the test: frames identical to in process, every
// wrong party refused with an error that says what is wrong, the server
// serving on after each; a stalled handshake dropped; no plain TCP beyond
// loopback unless asked for.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "client/farm/distributed_tile_service.h"
#include "common/base/error.h"
#include "common/render/frame.h"
#include "tests/support/background_server.h"
#include "server/log.h"
#include "server/server.h"
#include "tests/support/test_support.h"
#include "tests/support/message_stream.h"
#include "tests/support/glintd_process.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using server::test::GlintdProcess;

// Two CAs: "farm" signs the servers and the good client; "other" signs a
// stranger's client and a stranger's server.
class Tls : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("glint-tls-" + std::to_string(::getpid()));
    const std::string certs = test::sourcePath("deploy/glint-certs");
    const auto make = [&certs](const std::string& args) {
      const std::string command = certs + " " + args + " > /dev/null";
      ASSERT_EQ(std::system(command.c_str()), 0) << command;
    };
    make(path("farm") + " ca");
    make(path("farm") + " server glintd 127.0.0.1 localhost");
    make(path("farm") + " server elsewhere 127.0.0.2");
    make(path("farm") + " client alice");
    make(path("other") + " ca");
    make(path("other") + " client mallory");
    make(path("other") + " server impostor 127.0.0.1");
    signDated("farm", "stale", "clientAuth", "", "20200101000000Z", "20210101000000Z");
    signDated("farm", "early", "clientAuth", "", "20400101000000Z", "20410101000000Z");
    signDated("farm", "lapsed", "serverAuth", "IP:127.0.0.1", "20200101000000Z", "20210101000000Z");
  }
  // A certificate of CA `ca` valid from `start` to `end` (openssl ca, which
  // can date one in the past or the future; deploy/glint-certs cannot).
  static void signDated(const std::string& ca, const std::string& name, const std::string& usage,
                        const std::string& san, const std::string& start, const std::string& end) {
    const std::string d = path(ca);
    std::ofstream(d + "/dated.cnf") << "[ca]\ndefault_ca=d\n[d]\ndatabase=" << d << "/index\nnew_certs_dir=" << d
                                    << "\nserial=" << d << "/serial\ndefault_md=sha256\npolicy=p\n[p]\n"
                                    << "commonName=supplied\n";
    std::ofstream(d + "/dated.ext") << "extendedKeyUsage=" << usage << "\n"
                                    << (san.empty() ? "" : "subjectAltName=" + san + "\n");
    std::ofstream(d + "/index", std::ios::app).flush();
    if (!fs::exists(d + "/serial")) std::ofstream(d + "/serial") << "1000\n";
    const std::string command =
        "openssl req -new -newkey ec -pkeyopt ec_paramgen_curve:P-256 -nodes -subj /CN=" + name + " -keyout " + d +
        "/" + name + ".key -out " + d + "/" + name + ".csr 2> /dev/null && openssl ca -batch -config " + d +
        "/dated.cnf -cert " + d + "/ca.pem -keyfile " + d + "/ca.key -startdate " + start + " -enddate " + end +
        " -extfile " + d + "/dated.ext -in " + d + "/" + name + ".csr -out " + d + "/" + name + ".pem > /dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static std::string path(const std::string& name) { return (dir_ / name).string(); }

  static std::vector<std::string> serverArgs(const std::string& ca, const std::string& name) {
    return {"--threads",           "1",
            "--handshake-timeout", "0.5",
            "--tls-cert",          path(ca + "/" + name + ".pem"),
            "--tls-key",           path(ca + "/" + name + ".key"),
            "--tls-client-ca",     path("farm/ca.pem")};
  }
  // A client of CA `ca` (its certificate `name`; "" none) trusting `trust`.
  static DistributedSettings client(const std::string& trust, const std::string& ca, const std::string& name) {
    DistributedSettings s;
    s.tls.ca = path(trust + "/ca.pem");
    if (!name.empty()) {
      s.tls.cert = path(ca + "/" + name + ".pem");
      s.tls.key = path(ca + "/" + name + ".key");
    }
    s.timeouts.connect = std::chrono::seconds(3);
    return s;
  }
  static std::string refusal(const std::string& address, const DistributedSettings& settings) {
    try {
      DistributedTileService service(resolveServers({address}), room_.bundle, settings);
      return "(served)";
    } catch (const InputError& e) {
      return e.what();
    }
  }
  static FrameImage render(const std::string& address, const DistributedSettings& settings) {
    DistributedTileService service(resolveServers({address}), room_.bundle, settings);
    return renderFrame(service, frame(), {}).image;
  }
  static FrameSettings frame() {
    FrameSettings f = room_.scene.frame;
    f.width = 96;
    f.height = 72;
    return f;
  }
  static FrameImage inProcess() {
    const PreparedScene prepared(room_.scene, BvhSettings{});
    ThreadPool pool(2);
    LocalTileService service(prepared, pool);
    return renderFrame(service, frame(), {}).image;
  }

  static inline fs::path dir_;
  static inline proto::LoadedBundle room_ = proto::loadSceneBundle(test::sourcePath("scenes/room.json"));
};

TEST_F(Tls, FramesThroughTlsEqualInProcessFrames) {
  GlintdProcess a(serverArgs("farm", "glintd")), b(serverArgs("farm", "glintd"));
  EXPECT_NE(a.listeningLine().find(", TLS 1.3, client certificates required"), std::string::npos)
      << a.listeningLine();
  DistributedTileService service(resolveServers({a.address(), b.address()}), room_.bundle,
                                 client("farm", "farm", "alice"));
  EXPECT_EQ(renderFrame(service, frame(), {}).image.rgb, inProcess().rgb);
  // The name the certificate gives works as well as the address.
  EXPECT_EQ(render("localhost:" + std::to_string(a.port()), client("farm", "farm", "alice")).rgb, inProcess().rgb);
}

TEST_F(Tls, EachWrongPartyIsRefusedSayingWhyAndTheServerServesOn) {
  GlintdProcess glintd(serverArgs("farm", "glintd"));
  const std::string address = glintd.address();
  const FrameImage expected = inProcess();
  struct Case {
    const char* who;
    DistributedSettings settings;
    const char* says;
  };
  DistributedSettings plain;
  plain.timeouts.connect = std::chrono::seconds(3);
  const Case cases[] = {
      {"a plain client", plain, "closed the connection before answering Hello (does it want TLS?"},
      {"a client without a certificate", client("farm", "", ""), "the server refused our certificate"},
      {"a client of another CA", client("farm", "other", "mallory"), "the server refused our certificate"},
  };
  for (const Case& c : cases) {
    const std::string why = refusal(address, c.settings);
    EXPECT_NE(why.find("server " + address + ": unreachable, " + c.says), std::string::npos) << c.who << ": " << why;
    EXPECT_EQ(render(address, client("farm", "farm", "alice")).rgb, expected.rgb) << "after " << c.who;
  }
}

TEST_F(Tls, AServerTheClientCannotTrustIsRefused) {
  GlintdProcess impostor(serverArgs("other", "impostor"));
  const std::string untrusted = refusal(impostor.address(), client("farm", "farm", "alice"));
  EXPECT_NE(untrusted.find("the server's certificate is not trusted by --tls-ca or not for this address"),
            std::string::npos)
      << untrusted;
  // Signed by the right CA, but for another address.
  GlintdProcess elsewhere(serverArgs("farm", "elsewhere"));
  const std::string misaddressed = refusal(elsewhere.address(), client("farm", "farm", "alice"));
  EXPECT_NE(misaddressed.find("not for this address (IP address mismatch)"), std::string::npos) << misaddressed;
  // A TLS client at a plain server.
  GlintdProcess plain({"--threads", "1"});
  const std::string notTls = refusal(plain.address(), client("farm", "farm", "alice"));
  EXPECT_NE(notTls.find("the server is not speaking TLS 1.3"), std::string::npos) << notTls;
}

// A peer that opens a connection and never starts the handshake is dropped
// after the handshake timeout, like one that never says Hello.
TEST_F(Tls, AStalledHandshakeIsDropped) {
  GlintdProcess glintd(serverArgs("farm", "glintd"));
  proto::MessageStream stalled({asio::ip::make_address("127.0.0.1"), glintd.port()}, std::chrono::seconds(3));
  try {
    stalled.receive();
    FAIL() << "the server sent a message";
  } catch (const proto::StreamError& e) {
    EXPECT_EQ(e.kind(), proto::StreamError::Kind::kClosed) << e.what();
  }
  EXPECT_EQ(render(glintd.address(), client("farm", "farm", "alice")).rgb, inProcess().rgb);
}

// Without TLS, glintd listens on loopback only unless --insecure is given.
TEST_F(Tls, PlainTcpBeyondLoopbackNeedsInsecure) {
  server::setLogging(false);
  server::ServerOptions o;
  o.listen = "0.0.0.0:0";
  o.handleSignals = false;
  try {
    server::Server refused(o);
    FAIL() << "listened on 0.0.0.0 without TLS";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--listen 0.0.0.0:0: not a loopback address, and without TLS"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("--insecure"), std::string::npos) << e.what();
  }
  o.insecure = true;
  EXPECT_NO_THROW(server::Server accepted(o));
  o.insecure = false;
  o.tls = {path("farm/ca.pem"), path("farm/glintd.pem"), path("farm/glintd.key")};
  EXPECT_NO_THROW(server::Server secured(o));
  o.tls.key = path("farm/alice.key");
  try {
    server::Server mismatched(o);
    FAIL() << "took a key that is not the certificate's";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--tls-key " + path("farm/alice.key") +
                                         ": not a PEM private key, or not "
                                         "the key of --tls-cert"),
              std::string::npos)
        << e.what();
  }
}

// A certificate out of its dates, or made for the other end, is refused with
// that reason on both sides (not as "not signed by --tls-client-ca").
TEST_F(Tls, CertificatesOutOfDateOrForTheOtherEndAreNamedSo) {
  server::ServerOptions o;
  o.listen = "127.0.0.1:0";
  o.handleSignals = false;
  o.threads = 1;
  o.tls = {path("farm/ca.pem"), path("farm/glintd.pem"), path("farm/glintd.key")};
  server::setLogging(true);
  testing::internal::CaptureStderr();
  std::vector<std::string> clientSide;
  {
    server::BackgroundServer glintd(o);
    for (const char* name : {"stale", "early", "glintd"})
      clientSide.push_back(refusal(glintd.address(), client("farm", "farm", name)));
    // A client may read the server's alert before the server has logged its
    // reason; a whole frame served after the refusals orders the log before
    // the shutdown below (and shows the server serving on).
    EXPECT_EQ(render(glintd.address(), client("farm", "farm", "alice")).rgb, inProcess().rgb);
  }
  const std::string log = testing::internal::GetCapturedStderr();
  server::setLogging(false);
  EXPECT_NE(clientSide[0].find("the server refused our certificate: it has expired"), std::string::npos)
      << clientSide[0];
  EXPECT_NE(clientSide[1].find("the server refused our certificate"), std::string::npos) << clientSide[1];
  EXPECT_NE(clientSide[2].find("the server refused our certificate: it is not a client's"), std::string::npos)
      << clientSide[2];
  for (const char* says : {"the client's certificate has expired", "the client's certificate is not valid yet",
                           "the client's certificate is not a client's (extendedKeyUsage clientAuth"}) {
    EXPECT_NE(log.find(says), std::string::npos) << says << " not in:\n" << log;
  }
  // And a server whose certificate has expired, seen from the client.
  GlintdProcess lapsed(serverArgs("farm", "lapsed"));
  const std::string why = refusal(lapsed.address(), client("farm", "farm", "alice"));
  EXPECT_NE(why.find("the server's certificate has expired"), std::string::npos) << why;
}

}  // namespace
}  // namespace glint
