// libFuzzer target: everything glintd does with a client's bytes short of
// the socket. The input is a stream of frames; each verified message goes to
// a Session whose host builds scenes and traces (small) tiles at once.
#include <cstddef>
#include <cstdint>

#include "server/log.h"
#include "server/scene_cache.h"
#include "server/session.h"
#include "tests/fuzz/fuzz_messages.h"
#include "tests/support/inline_host.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint::server;
  setLogging(false);
  SceneCache cache(std::size_t{64} << 20);
  FileStore files(std::size_t{64} << 20);
  glint::MemoryGauge uploads(std::size_t{64} << 20, "fuzz uploads");
  test::InlineHost host(std::size_t{64} << 20, 4096);
  Session session(host, {cache, files, uploads}, {1 << 20, 1, 4, std::size_t{16} << 20}, "fuzz");
  host.attach(session);
  glint::fuzz::forEachMessage(
      data, size, [&session](const glint::wire::Message& m) { session.handle(m); },
      [&session] { return session.state() != Session::State::kEnded; });
  return 0;
}
