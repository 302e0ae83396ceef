#include "client/farm/server_link.h"

namespace glint {
namespace {

// A write gathers about this much, so that an upload's progress is seen a
// piece at a time.
constexpr std::size_t kGatherBytes = 1 << 20;

}  // namespace

ServerLink::ServerLink(asio::io_context& io, std::unique_ptr<proto::ByteStream> stream, std::size_t index,
                       std::string name, const proto::SceneBundle& bundle, const proto::BundleDigest& digest,
                       const LinkTimeouts& timeouts)
    : pipe_(std::move(stream), kGatherBytes),
      timer_(io),
      index_(index),
      name_(std::move(name)),
      conversation_(*this, bundle, digest, timeouts) {}

void ServerLink::start(LinkListener& listener) {
  listener_ = &listener;
  pipe_.start(shared_from_this());
  conversation_.start();
  pipe_.stream().open([self = shared_from_this()](const std::string& failure) {
    if (!failure.empty()) return self->conversation_.fail(LinkFailure::Kind::kUnreachable, failure);
    if (self->conversation_.over()) return;
    self->conversation_.connected();
    self->pipe_.read();
  });
}

void ServerLink::detach() {
  listener_ = nullptr;
  conversation_.fail(LinkFailure::Kind::kClosed, "dropped by the client");
}

void ServerLink::close() {
  listener_ = nullptr;
  conversation_.close();
}

void ServerLink::await(std::chrono::milliseconds timeout) {
  timer_.expires_after(timeout);
  timer_.async_wait([self = shared_from_this()](const asio::error_code& e) {
    if (!e) self->conversation_.timedOut();  // else cancelled: the awaited answer came
  });
}

void ServerLink::serving() {
  if (listener_) listener_->linkReady(*this);
}

void ServerLink::delivered(std::uint32_t frameId, std::uint32_t tileId, TileOutput&& out) {
  if (listener_) listener_->linkResult(*this, frameId, tileId, std::move(out));
}

void ServerLink::lost(const LinkFailure& failure) {
  pipe_.stream().close();
  if (listener_) listener_->linkFailed(*this, failure);
}

void ServerLink::send(std::vector<std::uint8_t> frame) { pipe_.send(std::move(frame)); }

void ServerLink::refused(const proto::Decoded& bad) {
  conversation_.fail(LinkFailure::Kind::kBadBytes, "sent a bad message: " + bad.error);
}

void ServerLink::readFailed(const asio::error_code& error) {
  conversation_.streamEnded(pipe_.stream().describe(error));
}

// Closing, the stream closes once Goodbye is written, whatever the write's end.
void ServerLink::writeFailed(const asio::error_code& error) {
  if (closing()) return pipe_.stream().close();
  conversation_.fail(LinkFailure::Kind::kClosed, "sending failed: " + pipe_.stream().describe(error));
}

void ServerLink::drained() {
  if (closing()) pipe_.stream().close();
}

}  // namespace glint
