#include "client/server_link.h"

namespace glint {
namespace {

constexpr std::size_t kReadChunkBytes = 64 * 1024;
constexpr std::size_t kGatherBytes = 1 << 20;

}  // namespace

ServerLink::ServerLink(asio::io_context& io, std::unique_ptr<LinkStream> stream, std::size_t index, std::string name,
                       const asio::ip::tcp::endpoint& endpoint, const proto::SceneBundle& bundle,
                       const proto::BundleDigest& digest, const LinkTimeouts& timeouts)
    : stream_(std::move(stream)),
      timer_(io),
      index_(index),
      name_(std::move(name)),
      endpoint_(endpoint),
      conversation_(*this, bundle, digest, timeouts) {}

void ServerLink::start(LinkListener& listener) {
  listener_ = &listener;
  conversation_.start();
  stream_->connect(endpoint_, [self = shared_from_this()](const std::string& failure) {
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
    for (std::size_t i = 0; i < self->inFlight_; ++i) self->writes_.pop_front();
    self->inFlight_ = 0;
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
  const std::size_t had = buffer_.size();
  buffer_.resize(had + kReadChunkBytes);
  stream_->readSome(asio::buffer(buffer_.data() + had, kReadChunkBytes),
                    [self = shared_from_this(), had](const asio::error_code& error, std::size_t n) {
                      self->buffer_.resize(had + n);
                      self->onRead(error, n);
                    });
}

// Hands every whole message that arrived to the conversation, in order;
// keeps a partial one.
void ServerLink::onRead(const asio::error_code& error, std::size_t n) {
  if (conversation_.over()) return;
  if (error) return conversation_.streamEnded(stream_->describe(error));
  received_ += n;
  std::size_t consumed = 0;
  while (!conversation_.over()) {
    const std::span<const std::uint8_t> unread(buffer_.data() + consumed, buffer_.size() - consumed);
    const proto::Decoded d = proto::decodeFrame(unread, proto::kDefaultMaxMessageBytes, aligned_);
    if (d.status == proto::DecodeStatus::kNeedMore) break;
    if (d.status == proto::DecodeStatus::kBad) return conversation_.fail(LinkFailure::Kind::kBadBytes, "sent a bad message: " + d.error);
    consumed += d.consumed;
    conversation_.handle(*d.message);
  }
  if (conversation_.over()) return;
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(consumed));
  readMore();
}

}  // namespace glint
