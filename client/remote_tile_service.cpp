#include "client/remote_tile_service.h"

#include <algorithm>

#include "common/error.h"
#include "proto/messages.h"
#include "proto/endpoint.h"

namespace glint {
namespace {

// Requests in flight at once per server thread: a whole frame of 64-pixel
// tiles fits, which halves the wake-ups of a small window (docs/performance.md).
constexpr std::size_t kWindowPerThread = 64;

}  // namespace

RemoteTileService::RemoteTileService(const std::string& address, const proto::SceneBundle& bundle,
                                     std::chrono::milliseconds timeout)
    : address_(address), timeout_(timeout), socket_(io_) {
  const asio::ip::tcp::endpoint endpoint = proto::parseEndpoint(address, "--server");
  asio::error_code connectError = asio::error::timed_out;
  socket_.async_connect(endpoint, [&](const asio::error_code& e) { connectError = e; });
  io_.run_for(timeout_);
  if (connectError) {
    asio::error_code ignored;
    socket_.close(ignored);
    fail("cannot connect (" + connectError.message() + "); is glintd running there?");
  }
  asio::error_code ignored;
  socket_.set_option(asio::ip::tcp::no_delay(true), ignored);

  send(proto::encodeHello(static_cast<std::uint32_t>(maxMessageBytes_), 0, "glint 0.1"));
  const wire::Message& hello = receive();
  throwIfError(hello);
  if (!hello.body_as_Hello()) fail("the server did not answer Hello");
  maxMessageBytes_ = std::min<std::size_t>(maxMessageBytes_, hello.body_as_Hello()->max_message_bytes());
  traffic_.serverThreads = static_cast<int>(hello.body_as_Hello()->threads());

  hash_ = bundle.hash();
  send(proto::encodeSceneQuery(hash_));
  const wire::Message& status = receive();
  throwIfError(status);
  if (!status.body_as_SceneStatus()) fail("the server did not answer the scene query");
  if (!status.body_as_SceneStatus()->present()) {
    const std::vector<std::uint8_t> upload = proto::encodeSceneUpload(hash_, bundle);
    if (upload.size() - proto::kHeaderBytes > maxMessageBytes_) {
      fail("the scene and its files (" + std::to_string(upload.size()) + " bytes) are over the server's limit of " +
           std::to_string(maxMessageBytes_) + " bytes; start glintd with a larger --max-message-mb");
    }
    send(upload);
    traffic_.uploaded = true;
    const wire::Message& ready = receive();
    throwIfError(ready);
    if (!ready.body_as_SceneReady()) fail("the server did not confirm the scene");
  }
}

RemoteTileService::~RemoteTileService() {
  if (!socket_.is_open()) return;
  try {
    send(proto::encodeGoodbye());
  } catch (const std::exception&) {
    // The server went away first: nothing to say goodbye to.
  }
}

void RemoteTileService::fail(const std::string& what) const { throw InputError("server " + address_ + ": " + what); }

void RemoteTileService::throwIfError(const wire::Message& m) const {
  if (const auto* e = m.body_as_Error()) {
    fail(std::string(wire::EnumNameErrorCode(e->code())) + ": " + (e->message() ? e->message()->str() : ""));
  }
}

void RemoteTileService::send(const std::vector<std::uint8_t>& frame) {
  asio::error_code error = asio::error::timed_out;
  asio::async_write(socket_, asio::buffer(frame), [&](const asio::error_code& e, std::size_t) { error = e; });
  io_.restart();
  if (io_.run_for(timeout_) == 0 || error) {
    asio::error_code ignored;
    socket_.close(ignored);
    fail("sending failed (" + error.message() + ")");
  }
  traffic_.bytesSent += frame.size();
}

const wire::Message& RemoteTileService::receive() {
  while (true) {
    const std::span<const std::uint8_t> unread(buffer_.data() + consumed_, buffer_.size() - consumed_);
    const proto::Decoded d = proto::decodeFrame(unread, proto::kDefaultMaxMessageBytes);
    if (d.status == proto::DecodeStatus::kBad) fail("sent a bad message: " + d.error);
    if (d.status == proto::DecodeStatus::kGood) {
      // The message stays where it is until the next receive().
      const std::uint8_t* body = unread.data() + proto::kHeaderBytes;
      consumed_ += d.consumed;
      traffic_.bytesReceived += d.consumed;
      return *wire::GetMessage(body);
    }
    // Drop what was consumed before reading more (the caller is done with it).
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(consumed_));
    consumed_ = 0;
    std::array<std::uint8_t, 65536> chunk;
    asio::error_code error = asio::error::timed_out;
    std::size_t got = 0;
    socket_.async_read_some(asio::buffer(chunk), [&](const asio::error_code& e, std::size_t n) {
      error = e;
      got = n;
    });
    io_.restart();
    io_.run_for(timeout_);
    if (error == asio::error::timed_out) {
      asio::error_code ignored;
      socket_.close(ignored);
      io_.restart();
      io_.run();  // let the cancelled read finish
      fail("no answer within " + std::to_string(timeout_.count()) + " ms");
    }
    if (error) fail(error == asio::error::eof ? "closed the connection" : "receiving failed (" + error.message() + ")");
    buffer_.insert(buffer_.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(got));
  }
}

void RemoteTileService::render(const FrameSettings& frame, std::span<const TileJob> jobs,
                               const std::function<void(std::size_t, TileOutput&&)>& done) {
  const std::uint32_t frameId = nextFrame_++;
  send(proto::encodeFrameSetup(frameId, hash_, frame));
  const std::size_t window = kWindowPerThread * static_cast<std::size_t>(std::max(1, traffic_.serverThreads));
  std::size_t next = 0;
  std::size_t outstanding = 0;
  std::size_t finished = 0;
  while (finished < jobs.size()) {
    // Tiles without a masked pixel are never sent; the others go out in
    // batches, one write for all requests that fit the window.
    std::vector<std::uint8_t> batch;
    while (next < jobs.size() && outstanding < window) {
      const TileJob& job = jobs[next];
      if (!job.mask.empty() && countMasked(job.rect, job.mask) == 0) {
        done(next++, TileOutput{});
        ++finished;
        continue;
      }
      const auto request = proto::encodeTileRequest(frameId, static_cast<std::uint32_t>(next), job.rect, job.mask);
      batch.insert(batch.end(), request.begin(), request.end());
      ++next;
      ++outstanding;
    }
    if (!batch.empty()) send(batch);
    if (outstanding == 0) continue;
    const wire::Message& m = receive();
    throwIfError(m);
    const auto* result = m.body_as_TileResult();
    if (!result || result->frame_id() != frameId || result->tile_id() >= jobs.size()) {
      fail("sent an unexpected message during frame " + std::to_string(frameId));
    }
    TileOutput out;
    if (result->rgb()) out.rgb.assign(result->rgb()->begin(), result->rgb()->end());
    out.rays = proto::decodeRays(result->rays());
    done(result->tile_id(), std::move(out));
    --outstanding;
    ++finished;
  }
}

}  // namespace glint
