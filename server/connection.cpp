#include "server/connection.h"

#include <unordered_set>

#include "common/base/timing.h"
#include "server/log.h"

namespace glint::server {
namespace {

Session::Settings sessionSettings(const ServerContext& context) {
  return {static_cast<std::uint32_t>(context.options.maxMessageBytes),
          static_cast<std::uint32_t>(context.scheduler.threads()), static_cast<std::size_t>(context.options.maxClients),
          context.options.maxSceneBytes};
}

}  // namespace

Connection::Connection(std::unique_ptr<proto::ByteStream> stream, ServerContext& context, std::uint64_t id,
                       std::string peer)
    : stream_(std::move(stream)),
      timer_(context.io),
      context_(context),
      id_(id),
      outbox_(context.scheduler.threads()),
      session_(*this, {context.cache, context.files, context.buildMemory}, sessionSettings(context), std::move(peer)) {}

// Before Hello comes the TLS handshake (at once over plain TCP), under the
// same timeout and in the same waiting pool: a peer that starts one and
// stalls holds little, briefly.
void Connection::start() {
  logLine(session_.peer() + ": connected");
  armTimer(context_.options.handshakeTimeout, "TLS handshake");
  stream_->open([self = shared_from_this()](const std::string& failure) {
    if (!failure.empty()) return self->close("TLS handshake failed: " + failure);
    self->waitForMessage();
    self->read();
  });
}

void Connection::armTimer(std::chrono::milliseconds timeout, const char* what) {
  timer_.expires_after(timeout);
  timer_.async_wait([self = shared_from_this(), what](const asio::error_code& error) {
    if (!error && !self->closed_) self->onTimer(what);  // else re-armed or closed
  });
}

// What a silent client holds is freed: a message started and not finished,
// a connection with nothing to do, a client that stopped reading its results.
void Connection::onTimer(const char* what) {
  if (reader_.midMessage()) {
    close(greeted() ? "read timeout: a message was not finished" : "handshake timeout: no Hello");
  } else if (pending_ > 0) {
    armTimer(context_.options.idleTimeout, what);  // our own work is not idleness
  } else if (writes_.writing()) {
    if (Clock::now() - lastWrite_ > context_.options.readTimeout) {
      close("client stopped reading its results");
    } else {
      armTimer(context_.options.readTimeout, what);
    }
  } else {
    close(std::string(what) + " timeout");
  }
}

void Connection::read() {
  if (closed_ || closeAfterWrites_) return;
  const std::span<std::uint8_t> space = reader_.space();
  stream_->readSome(asio::buffer(space.data(), space.size()), [self = shared_from_this()](const asio::error_code& error,
                                                                                          std::size_t n) {
    if (error) {
      const bool mid = self->reader_.midMessage();
      self->close(error == asio::error::eof ? (mid ? "disconnected mid-message" : "disconnected") : error.message());
      return;
    }
    const bool wasMid = self->reader_.midMessage();
    self->reader_.filled(n);
    self->takeMessages(wasMid);
  });
}

// Hands every whole message that arrived to the session, then reads on
// (`wasMid`: part of a message was held before these bytes). A message
// started arms the read timeout once (before Hello the handshake's
// deadline stands: a header does not buy a connection more time); a
// connection between messages waits under the idle or handshake timeout.
void Connection::takeMessages(bool wasMid) {
  bool took = false;
  while (!closed_ && !closeAfterWrites_) {
    const std::size_t limit = greeted() ? context_.options.maxMessageBytes : ServerOptions::kMaxHandshakeMessageBytes;
    const proto::Decoded d = reader_.next(limit);
    if (d.status == proto::DecodeStatus::kNeedMore) break;
    if (d.status == proto::DecodeStatus::kBad) {
      const bool tooLarge = d.code == wire::ErrorCode::TooLarge;
      const std::string hint = greeted() ? " (is this a Glint client?)" : " before Hello (is this a Glint client?)";
      return session_.error(d.code, d.error + (tooLarge ? hint : ""), true);
    }
    took = true;
    session_.handle(*d.message);
  }
  if (closed_ || closeAfterWrites_) return;
  const bool mid = reader_.midMessage();
  if (mid && (took || !wasMid) && greeted()) armTimer(context_.options.readTimeout, "read");
  if (!mid && took) waitForMessage();
  read();
}

void Connection::waitForMessage() {
  armTimer(greeted() ? context_.options.idleTimeout : context_.options.handshakeTimeout,
           greeted() ? "idle" : "handshake");
}

void Connection::end(const std::string& why) {
  logLine(session_.peer() + ": " + why);
  closeAfterWrites_ = true;
  if (!writes_.writing()) close(why);
}

void Connection::build(SceneJob job) {
  ++pending_;
  context_.builds.build(std::move(job), [self = shared_from_this()](const BuiltScene& built) {
    asio::post(self->context_.io, [self, built] {
      --self->pending_;
      if (!self->closed_) self->session_.sceneBuilt(built);
    });
  });
}

void Connection::trace(TileWork work) {
  ++pending_;
  outbox_.expect();
  const std::uint64_t tag = proto::tileKey(work.frameId, work.tileId);
  context_.scheduler.submit(
      id_,
      [self = shared_from_this(), work = std::move(work)] {
        if (self->outbox_.put(traceTile(work))) asio::post(self->context_.io, [self] { self->takeOutbox(); });
      },
      tag);
}

void Connection::cancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds) {
  const std::unordered_set<std::uint32_t> tiles(tileIds.begin(), tileIds.end());
  const std::size_t dropped = context_.scheduler.cancel(id_, [&](std::uint64_t tag) {
    return tag >> 32 == frameId && (tiles.empty() || tiles.contains(static_cast<std::uint32_t>(tag)));
  });
  if (dropped == 0) return;
  pending_ -= static_cast<int>(dropped);
  if (outbox_.forget(dropped)) takeOutbox();
}

void Connection::takeOutbox() {
  std::vector<std::vector<std::uint8_t>> results = outbox_.take();
  pending_ -= static_cast<int>(results.size());
  for (auto& r : results) reply(std::move(r));
}

void Connection::reply(std::vector<std::uint8_t> frame) {
  if (closed_) return;
  const std::size_t queued = writes_.queuedBytes() + frame.size();
  if (queued > context_.options.maxQueuedBytes) {
    close("client is not reading its results (" + std::to_string(queued) + " bytes queued)");
    return;
  }
  writes_.push(std::move(frame));
  if (!writes_.writing()) writeNext();
}

// Everything queued goes out in one gathered write (one system call for many
// small tile results); new results queue up behind it.
void Connection::writeNext() {
  if (closed_) return;
  const std::vector<std::span<const std::uint8_t>> frames = writes_.next(SIZE_MAX);
  if (frames.empty()) {
    if (closeAfterWrites_) close("closed after its last reply");
    return;
  }
  lastWrite_ = Clock::now();
  std::vector<asio::const_buffer> buffers;
  for (const auto& frame : frames) buffers.push_back(asio::buffer(frame.data(), frame.size()));
  stream_->write(buffers, [self = shared_from_this()](const asio::error_code& error, std::size_t) {
    if (error) return self->close(error.message());
    self->writes_.written();
    self->writeNext();
  });
}

void Connection::close(const std::string& why) {
  if (closed_) return;
  closed_ = true;
  context_.registry.remove(id_);
  const std::size_t dropped = context_.scheduler.cancel(id_);
  pending_ -= static_cast<int>(dropped);
  timer_.cancel();
  stream_->close();
  logLine(session_.peer() + ": closed (" + why +
          (dropped ? ", " + std::to_string(dropped) + " queued tiles cancelled" : "") + ")");
}

}  // namespace glint::server
