#include "client/remote_tile_service.h"

#include <algorithm>

#include "common/error.h"
#include "proto/messages.h"
#include "proto/endpoint.h"
#include "proto/message_stream.h"

namespace glint {
namespace {

// Requests in flight at once per server thread: a whole frame of 64-pixel
// tiles fits, which halves the wake-ups of a small window (docs/performance.md).
constexpr std::size_t kWindowPerThread = 64;

// The RGB bytes a tile's result carries.
std::size_t pixelBytes(const TileJob& job) {
  return 3 * (job.mask.empty() ? job.rect.pixelCount() : countMasked(job.rect, job.mask));
}

}  // namespace

RemoteTileService::RemoteTileService(const std::string& address, const proto::SceneBundle& bundle,
                                     std::chrono::milliseconds timeout)
    : address_(address) {
  const asio::ip::tcp::endpoint endpoint = proto::parseEndpoint(address, "--server");
  try {
    stream_ = std::make_unique<proto::MessageStream>(endpoint, timeout);
  } catch (const proto::StreamError& e) {
    fail(std::string(e.what()) + "; is glintd running there?");
  }
  send(proto::encodeHello(static_cast<std::uint32_t>(maxMessageBytes_), 0, "glint 0.1"));
  const wire::Hello* hello = receive().body_as_Hello();
  if (!hello) fail("the server did not answer Hello");
  maxMessageBytes_ = std::min<std::size_t>(maxMessageBytes_, hello->max_message_bytes());
  constexpr std::uint32_t kMaxThreadsBelieved = 4096;  // sizes the request window, nothing more
  serverThreads_ = static_cast<int>(std::min(hello->threads(), kMaxThreadsBelieved));

  hash_ = bundle.hash();
  send(proto::encodeSceneQuery(hash_));
  const wire::SceneStatus* status = receive().body_as_SceneStatus();
  if (!status) fail("the server did not answer the scene query");
  if (!status->present()) {
    const std::vector<std::uint8_t> upload = proto::encodeSceneUpload(hash_, bundle);
    if (upload.size() - proto::kHeaderBytes > maxMessageBytes_) {
      fail("the scene and its files (" + std::to_string(upload.size()) + " bytes) are over the server's limit of " +
           std::to_string(maxMessageBytes_) + " bytes; start glintd with a larger --max-message-mb");
    }
    send(upload);
    uploaded_ = true;
    if (!receive().body_as_SceneReady()) fail("the server did not confirm the scene");
  }
}

RemoteTileService::~RemoteTileService() {
  if (!stream_ || !stream_->isOpen()) return;
  try {
    stream_->send(proto::encodeGoodbye());
  } catch (const proto::StreamError&) {
    // The server went away first: nothing to say goodbye to.
  }
}

void RemoteTileService::fail(const std::string& what) const { throw InputError("server " + address_ + ": " + what); }

void RemoteTileService::send(const std::vector<std::uint8_t>& frame) {
  try {
    stream_->send(frame);
  } catch (const proto::StreamError& e) {
    stream_->close();
    fail(e.what());
  }
}

const wire::Message& RemoteTileService::receive() {
  try {
    const wire::Message& m = stream_->receive();
    if (const auto* e = m.body_as_Error()) {
      fail(std::string(wire::EnumNameErrorCode(e->code())) + ": " + (e->message() ? e->message()->str() : ""));
    }
    return m;
  } catch (const proto::StreamError& e) {
    stream_->close();
    fail(e.what());
  }
}

// The next result of frame `frameId`, checked: a tile that was requested
// (below `requested`), not delivered before, with one RGB triple per masked
// pixel. Anything else is a protocol error that ends the frame.
const wire::TileResult& RemoteTileService::receiveResult(std::uint32_t frameId, std::size_t requested,
                                                         std::span<const std::size_t> tileBytes,
                                                         std::vector<bool>& delivered) {
  const auto* result = receive().body_as_TileResult();
  if (!result || result->frame_id() != frameId || result->tile_id() >= requested || delivered[result->tile_id()]) {
    stream_->expect(0);
    fail("sent an unexpected message during frame " + std::to_string(frameId));
  }
  const std::uint32_t tile = result->tile_id();
  const std::size_t rgbBytes = result->rgb() ? result->rgb()->size() : 0;
  if (rgbBytes != tileBytes[tile]) {
    stream_->expect(0);
    fail("tile " + std::to_string(tile) + " of frame " + std::to_string(frameId) + " came with " +
         std::to_string(rgbBytes) + " bytes of pixels, not " + std::to_string(tileBytes[tile]));
  }
  delivered[tile] = true;
  return *result;
}

void RemoteTileService::render(const FrameSettings& frame, std::span<const TileJob> jobs,
                               const std::function<void(std::size_t, TileOutput&&)>& done) {
  const std::uint32_t frameId = nextFrame_++;
  send(proto::encodeFrameSetup(frameId, hash_, frame));
  const std::size_t window = kWindowPerThread * static_cast<std::size_t>(std::max(1, serverThreads_));
  std::size_t next = 0;
  std::size_t outstanding = 0;
  std::size_t finished = 0;
  // Pixel bytes of the requested tiles not yet received: the server sends at
  // least these without waiting for us. Promised to the stream only after the
  // frame's first result, so that an error about the frame itself comes back
  // at once.
  std::size_t owedBytes = 0;
  std::vector<std::size_t> tileBytes(jobs.size(), 0);  // of each requested tile
  std::vector<bool> delivered(jobs.size(), false);     // a second result for a tile is a protocol error
  bool started = false;
  while (finished < jobs.size()) {
    // Tiles without a masked pixel are never sent; the others go out in
    // batches, one write for all requests that fit the window.
    std::vector<std::uint8_t> batch;
    while (next < jobs.size() && outstanding < window) {
      const TileJob& job = jobs[next];
      tileBytes[next] = pixelBytes(job);
      if (!job.mask.empty() && tileBytes[next] == 0) {
        delivered[next] = true;
        done(next++, TileOutput{});
        ++finished;
        continue;
      }
      const auto request = proto::encodeTileRequest(frameId, static_cast<std::uint32_t>(next), job.rect, job.mask);
      batch.insert(batch.end(), request.begin(), request.end());
      owedBytes += tileBytes[next];
      ++next;
      ++outstanding;
    }
    if (!batch.empty()) send(batch);
    if (outstanding == 0) continue;
    stream_->expect(started ? owedBytes : 0);
    const wire::TileResult& result = receiveResult(frameId, next, tileBytes, delivered);
    const std::uint32_t tile = result.tile_id();
    started = true;
    owedBytes -= std::min(owedBytes, tileBytes[tile]);
    TileOutput out;
    if (result.rgb()) out.rgb.assign(result.rgb()->begin(), result.rgb()->end());
    out.rays = proto::decodeRays(result.rays());
    out.computeMs = result.compute_us() / 1000.0;
    done(tile, std::move(out));
    --outstanding;
    ++finished;
  }
  stream_->expect(0);
}

}  // namespace glint
