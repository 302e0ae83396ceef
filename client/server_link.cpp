#include "client/server_link.h"

namespace glint {
namespace {

constexpr std::size_t kGatherBytes = 1 << 20;

}  // namespace

ServerLink::ServerLink(asio::io_context& io, std::unique_ptr<proto::ByteStream> stream, std::size_t index,
                       std::string name, const proto::SceneBundle& bundle, const proto::BundleDigest& digest,
                       const LinkTimeouts& timeouts)
    : stream_(std::move(stream)),
      timer_(io),
      index_(index),
      name_(std::move(name)),
      conversation_(*this, bundle, digest, timeouts) {}

void ServerLink::start(LinkListener& listener) {
  listener_ = &listener;
  conversation_.start();
  stream_->open([self = shared_from_this()](const std::string& failure) {
    if (!failure.empty()) return self->conversation_.fail(LinkFailure::Kind::kUnreachable, failure);
    if (self->conversation_.over()) return;
    self->conversation_.connected();
    self->readMore();
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
  stream_->close();
  if (listener_) listener_->linkFailed(*this, failure);
}

void ServerLink::send(std::vector<std::uint8_t> frame) {
  writes_.push(std::move(frame));
  if (!writes_.writing()) writeNext();
}

// One write in flight, gathering the messages queued meanwhile up to about
// kGatherBytes, so that an upload's progress is seen a piece at a time.
void ServerLink::writeNext() {
  if (!stream_->isOpen()) return;
  std::vector<asio::const_buffer> buffers;
  for (const auto& frame : writes_.next(kGatherBytes)) buffers.push_back(asio::buffer(frame.data(), frame.size()));
  if (buffers.empty()) return;
  stream_->write(buffers, [self = shared_from_this()](const asio::error_code& error, std::size_t n) {
    self->sent_ += n;
    self->writes_.written();
    const bool closing = self->conversation_.state() == ServerConversation::State::kClosed;
    if (closing && self->writes_.empty()) self->stream_->close();
    if (!closing && error) {
      return self->conversation_.fail(LinkFailure::Kind::kClosed, "sending failed: " + self->stream_->describe(error));
    }
    self->conversation_.wrote(n);
    self->writeNext();
  });
}

void ServerLink::readMore() {
  const std::span<std::uint8_t> space = reader_.space();
  stream_->readSome(
      asio::buffer(space.data(), space.size()),
      [self = shared_from_this()](const asio::error_code& error, std::size_t n) { self->onRead(error, n); });
}

// Hands every whole message that arrived to the conversation, in order.
void ServerLink::onRead(const asio::error_code& error, std::size_t n) {
  if (conversation_.over()) return;
  if (error) return conversation_.streamEnded(stream_->describe(error));
  received_ += n;
  reader_.filled(n);
  while (!conversation_.over()) {
    const proto::Decoded d = reader_.next(proto::kDefaultMaxMessageBytes);
    if (d.status == proto::DecodeStatus::kNeedMore) return readMore();
    if (d.status == proto::DecodeStatus::kBad) {
      return conversation_.fail(LinkFailure::Kind::kBadBytes, "sent a bad message: " + d.error);
    }
    conversation_.handle(*d.message);
  }
}

}  // namespace glint
