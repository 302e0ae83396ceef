// libFuzzer target: everything glint does with one server's bytes short of
// the socket. A ServerLink runs over a stream whose reads are the input; once
// the link is ready it sets up a frame and asks for two tiles, so that
// results reach the checks of their frame, tile and size. The first byte:
// with bit 0 set the input speaks for the server from its first byte, Hello
// included; clear, a Hello of this build comes first (a seed cannot carry the
// fuzz build's identity, which the link demands). Its other bits set how many
// bytes a read gives (1 to 65,025).
#include <algorithm>
#include <cstring>
#include <span>

#include "client/farm/server_link.h"
#include "proto/messages.h"
#include "tests/fuzz/server_link_script.h"

namespace {

using namespace glint;

// Reads give the input, a piece at a time, then end of file; writes succeed.
class InputStream : public proto::ByteStream {
 public:
  InputStream(asio::io_context& io, std::span<const std::uint8_t> input, std::size_t piece)
      : io_(io), input_(input), piece_(piece) {}
  void open(std::function<void(const std::string&)> done) override {
    asio::post(io_, [done] { done(""); });
  }
  void write(const std::vector<asio::const_buffer>& buffers, Done done) override {
    const std::size_t n = asio::buffer_size(buffers);
    asio::post(io_, [done, n] { done({}, n); });
  }
  void readSome(asio::mutable_buffer buffer, Done done) override {
    const std::size_t n = std::min({buffer.size(), piece_, input_.size()});
    if (n > 0) std::memcpy(buffer.data(), input_.data(), n);
    input_ = input_.subspan(n);
    const asio::error_code error = n == 0 ? asio::error::eof : asio::error_code{};
    asio::post(io_, [done, error, n] { done(error, n); });
  }
  std::string describe(const asio::error_code& error) override { return error.message(); }
  void close() override { open_ = false; }
  bool isOpen() const override { return open_; }

 private:
  asio::io_context& io_;
  std::span<const std::uint8_t> input_;
  std::size_t piece_;
  bool open_ = true;
};

class Client : public LinkListener {
 public:
  void linkReady(ServerLink& link) override {
    FrameSettings frame;
    frame.width = 16;
    frame.height = 8;
    link.setupFrame(fuzz::kLinkFrame, frame);
    const std::vector<TileJob> jobs = fuzz::linkJobs();
    for (std::uint32_t tile = 0; tile < jobs.size(); ++tile) link.request(fuzz::kLinkFrame, tile, jobs[tile]);
  }
  void linkResult(ServerLink&, std::uint32_t, std::uint32_t, TileOutput&&) override {}
  void linkFailed(ServerLink&, const LinkFailure&) override {}
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const proto::BundleDigest digest = proto::digest(fuzz::linkBundle());
  std::vector<std::uint8_t> input;
  if ((data[0] & 1) == 0) input = proto::encodeHello(1 << 20, 2, "fuzz");
  input.insert(input.end(), data + 1, data + size);
  const std::size_t piece = 1 + static_cast<std::size_t>(data[0] >> 1) * 512;
  asio::io_context io;
  auto link = std::make_shared<ServerLink>(io, std::make_unique<InputStream>(io, input, piece), 0, "fuzz",
                                           fuzz::linkBundle(), digest, LinkTimeouts{});
  Client client;
  link->start(client);
  io.run();
  link->detach();
  return 0;
}
