#include "client/server_link.h"

#include <algorithm>

#include "common/base/build_identity.h"
#include "common/base/printable.h"
#include "proto/messages.h"

namespace glint {
namespace {

constexpr std::size_t kReadChunkBytes = 64 * 1024;
constexpr std::size_t kGatherBytes = 1 << 20;
constexpr const char* kSceneWait = "scene upload and build; --scene-timeout";
constexpr std::uint32_t kMaxThreadsBelieved = 4096;  // sizes the dispatcher's window, nothing more

std::uint64_t key(std::uint32_t frameId, std::uint32_t tileId) { return std::uint64_t{frameId} << 32 | tileId; }

}  // namespace

ServerLink::ServerLink(asio::io_context& io, std::unique_ptr<LinkStream> stream, std::size_t index, std::string name,
                       const asio::ip::tcp::endpoint& endpoint, const proto::SceneBundle& bundle,
                       const proto::BundleDigest& digest, const LinkTimeouts& timeouts)
    : stream_(std::move(stream)),
      timer_(io),
      index_(index),
      name_(std::move(name)),
      endpoint_(endpoint),
      bundle_(bundle),
      digest_(digest),
      timeouts_(timeouts) {}

void ServerLink::start(LinkListener& listener) {
  listener_ = &listener;
  armTimer(timeouts_.connect, "connecting");
  stream_->connect(endpoint_, [self = shared_from_this()](const std::string& failure) { self->onConnected(failure); });
}

void ServerLink::detach() {
  listener_ = nullptr;
  if (state_ != State::kFailed && state_ != State::kClosed) fail(LinkFailure::Kind::kClosed, "dropped by the client");
}

void ServerLink::armTimer(std::chrono::milliseconds timeout, const char* waitingFor) {
  timer_.expires_after(timeout);
  timer_.async_wait([self = shared_from_this(), waitingFor, timeout](const asio::error_code& e) {
    if (e) return;  // cancelled: the awaited answer came
    self->fail(LinkFailure::Kind::kUnreachable,
               std::string("no answer within ") + std::to_string(timeout.count() / 1000) + " s (" + waitingFor + ")");
  });
}

void ServerLink::onConnected(const std::string& failure) {
  if (state_ != State::kConnecting) return;
  if (!failure.empty()) {
    fail(LinkFailure::Kind::kUnreachable, failure);
    return;
  }
  state_ = State::kHello;
  armTimer(timeouts_.connect, "Hello");
  write(proto::encodeHello(static_cast<std::uint32_t>(maxMessageBytes_), 0, "glint 0.1"));
  readMore();
}

void ServerLink::fail(LinkFailure::Kind kind, const std::string& what) {
  if (state_ == State::kFailed || state_ == State::kClosed) return;
  state_ = State::kFailed;
  timer_.cancel();
  stream_->close();
  if (listener_) listener_->linkFailed(*this, {kind, what});
}

void ServerLink::close() {
  if (state_ == State::kFailed || state_ == State::kClosed) return;
  listener_ = nullptr;
  write(proto::encodeGoodbye());
  state_ = State::kClosed;
  timer_.cancel();
}

void ServerLink::write(std::vector<std::uint8_t> frame) {
  writes_.push_back(std::move(frame));
  if (inFlight_ == 0) writeNext();
}

// One write in flight, gathering the messages queued meanwhile up to about
// kGatherBytes, so that an upload's progress is seen a piece at a time.
void ServerLink::writeNext() {
  if (writes_.empty() || !stream_->isOpen()) return;
  std::vector<asio::const_buffer> buffers;
  std::size_t bytes = 0;
  for (inFlight_ = 0; inFlight_ < writes_.size() && (inFlight_ == 0 || bytes < kGatherBytes); ++inFlight_) {
    buffers.push_back(asio::buffer(writes_[inFlight_]));
    bytes += writes_[inFlight_].size();
  }
  stream_->write(buffers, [self = shared_from_this()](const asio::error_code& error, std::size_t n) {
    self->sent_ += n;
    if (self->state_ == State::kUpload && n > 0) self->armTimer(self->timeouts_.scene, kSceneWait);  // still moving
    for (std::size_t i = 0; i < self->inFlight_; ++i) self->writes_.pop_front();
    self->inFlight_ = 0;
    if (self->state_ == State::kClosed) {
      if (self->writes_.empty()) self->stream_->close();
    } else if (error) {
      self->fail(LinkFailure::Kind::kClosed, "sending failed: " + self->stream_->describe(error));
      return;
    }
    self->writeNext();
  });
}

void ServerLink::readMore() {
  const std::size_t had = buffer_.size();
  buffer_.resize(had + kReadChunkBytes);
  stream_->readSome(asio::buffer(buffer_.data() + had, kReadChunkBytes),
                    [self = shared_from_this(), had](const asio::error_code& error, std::size_t n) {
                      self->buffer_.resize(had + n);
                      self->onRead(error, n);
                    });
}

// Decodes every whole message that arrived, in order; keeps a partial one.
void ServerLink::onRead(const asio::error_code& error, std::size_t n) {
  if (state_ == State::kFailed || state_ == State::kClosed) return;
  if (error) {
    // Before the server's Hello, a close is a refusal: of our certificate
    // (TLS), of a client that speaks plain TCP to a TLS server, or of our Hello.
    const bool greeting = state_ == State::kHello;
    std::string why = stream_->describe(error);
    if (greeting && why == "closed the connection") {
      why = "closed the connection before answering Hello (does it want TLS? then give --tls-ca, --tls-cert and "
            "--tls-key)";
    }
    fail(greeting ? LinkFailure::Kind::kRefused : LinkFailure::Kind::kClosed, why);
    return;
  }
  received_ += n;
  std::size_t consumed = 0;
  while (state_ != State::kFailed) {
    const std::span<const std::uint8_t> unread(buffer_.data() + consumed, buffer_.size() - consumed);
    const proto::Decoded d = proto::decodeFrame(unread, proto::kDefaultMaxMessageBytes, aligned_);
    if (d.status == proto::DecodeStatus::kNeedMore) break;
    if (d.status == proto::DecodeStatus::kBad) {
      fail(LinkFailure::Kind::kBadBytes, "sent a bad message: " + d.error);
      return;
    }
    consumed += d.consumed;
    onMessage(*d.message);
  }
  if (state_ == State::kFailed) return;
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(consumed));
  readMore();
}

void ServerLink::onMessage(const wire::Message& m) {
  if (const auto* e = m.body_as_Error()) return onError(*e);
  if (state_ == State::kHello && m.body_type() == wire::Body::Hello) return onHello(*m.body_as_Hello());
  if (state_ == State::kQuery && m.body_type() == wire::Body::SceneStatus) {
    return onSceneStatus(*m.body_as_SceneStatus());
  }
  if (state_ == State::kUpload && m.body_type() == wire::Body::SceneReady) return becomeReady();
  if (state_ == State::kReady && m.body_type() == wire::Body::TileResult) return onResult(*m.body_as_TileResult());
  fail(LinkFailure::Kind::kBadBytes, std::string("sent an unexpected ") + proto::bodyName(m.body_type()) + " message");
}

void ServerLink::onHello(const wire::Hello& hello) {
  const std::string build = hello.build() ? hello.build()->str() : "(none)";
  if (build != buildIdentity()) {
    fail(LinkFailure::Kind::kRefused, "its pixels would differ from this client's (server build '" + printable(build) +
                                          "', client build '" + buildIdentity() +
                                          "'); run glint and glintd from the same build");
    return;
  }
  maxMessageBytes_ = std::min<std::size_t>(maxMessageBytes_, hello.max_message_bytes());
  threads_ = static_cast<int>(std::clamp<std::uint32_t>(hello.threads(), 1, kMaxThreadsBelieved));
  state_ = State::kQuery;
  write(proto::encodeSceneQuery(digest_.scene, digest_.files));
}

// The server lacks the scene: the files it lacks, in pieces within its
// message limit, then the scene's text and file list.
void ServerLink::onSceneStatus(const wire::SceneStatus& status) {
  if (status.present()) return becomeReady();
  std::vector<std::uint8_t> upload = proto::encodeSceneUpload(digest_.scene, bundle_, digest_.files);
  if (upload.size() - proto::kHeaderBytes > maxMessageBytes_) {
    fail(LinkFailure::Kind::kRefused, "the scene file's text (" + std::to_string(bundle_.text.size()) +
                                          " bytes) is over the server's message limit of " +
                                          std::to_string(maxMessageBytes_) +
                                          " bytes; start glintd with a larger --max-message-mb");
    return;
  }
  if (!sendMissingFiles(status)) return;
  state_ = State::kUpload;
  uploaded_ = true;
  armTimer(timeouts_.scene, kSceneWait);
  write(std::move(upload));
}

bool ServerLink::sendMissingFiles(const wire::SceneStatus& status) {
  std::vector<const std::string*> files;
  for (const auto& [path, bytes] : bundle_.files) files.push_back(&bytes);
  constexpr std::size_t kChunkOverhead = 4096;  // the FileChunk's own fields and framing
  const std::size_t chunkBytes =
      std::min(proto::kFileChunkBytes, maxMessageBytes_ > 2 * kChunkOverhead ? maxMessageBytes_ - kChunkOverhead
                                                                              : kChunkOverhead);
  if (!status.missing()) return true;
  std::vector<bool> sent(files.size(), false);  // a server asking twice gets a file once
  for (const std::uint32_t i : *status.missing()) {
    if (i >= files.size()) {
      fail(LinkFailure::Kind::kBadBytes, "asked for file " + std::to_string(i) + " of a scene of " +
                                             std::to_string(files.size()) + " files");
      return false;
    }
    if (sent[i]) continue;
    sent[i] = true;
    for (auto& chunk : proto::encodeFileChunks(*files[i], digest_.files[i], chunkBytes)) write(std::move(chunk));
  }
  return true;
}

void ServerLink::becomeReady() {
  state_ = State::kReady;
  timer_.cancel();
  if (listener_) listener_->linkReady(*this);
}

void ServerLink::onError(const wire::Error& error) {
  const std::string text = std::string(wire::EnumNameErrorCode(error.code())) + ": " +
                           (error.message() ? printable(error.message()->string_view()) : "");
  switch (error.code()) {
    case wire::ErrorCode::BadScene:
      return fail(LinkFailure::Kind::kSceneError, text);
    case wire::ErrorCode::Busy:
    case wire::ErrorCode::Version:
    case wire::ErrorCode::ShuttingDown:
      return fail(state_ == State::kReady ? LinkFailure::Kind::kServerError : LinkFailure::Kind::kRefused, text);
    default:
      return fail(LinkFailure::Kind::kServerError, text);
  }
}

void ServerLink::setupFrame(std::uint32_t frameId, const FrameSettings& frame) {
  if (frameId > proto::kFramesRemembered) {  // results of frames the server forgot will not come
    std::erase_if(pending_, [&](const auto& p) { return p.first >> 32 <= frameId - proto::kFramesRemembered; });
  }
  write(proto::encodeFrameSetup(frameId, digest_.scene, frame));
}

void ServerLink::request(std::uint32_t frameId, std::uint32_t tileId, const TileJob& job) {
  pending_[key(frameId, tileId)] = 3 * tracedPixels(job);
  write(proto::encodeTileRequest(frameId, tileId, job.rect, job.mask));
}

void ServerLink::cancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds) {
  if (state_ == State::kReady) write(proto::encodeCancel(frameId, tileIds));
}

// A result must answer a request of this link (a cancelled one may still
// come) with one RGB triple per masked pixel.
void ServerLink::onResult(const wire::TileResult& result) {
  const auto it = pending_.find(key(result.frame_id(), result.tile_id()));
  const std::string tile = "tile " + std::to_string(result.tile_id()) + " of frame " + std::to_string(result.frame_id());
  if (it == pending_.end()) {
    fail(LinkFailure::Kind::kBadBytes, "sent " + tile + ", which was not asked of it (or came twice)");
    return;
  }
  const std::size_t rgbBytes = result.rgb() ? result.rgb()->size() : 0;
  if (rgbBytes != it->second) {
    fail(LinkFailure::Kind::kBadBytes, "sent " + tile + " with " + std::to_string(rgbBytes) +
                                           " bytes of pixels, not " + std::to_string(it->second));
    return;
  }
  pending_.erase(it);
  TileOutput out;
  if (result.rgb()) out.rgb.assign(result.rgb()->begin(), result.rgb()->end());
  out.rays = proto::decodeRays(result.rays());
  out.computeMs = result.compute_us() / 1000.0;
  if (listener_) listener_->linkResult(*this, result.frame_id(), result.tile_id(), std::move(out));
}

}  // namespace glint
