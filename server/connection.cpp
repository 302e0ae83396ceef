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
    : pipe_(std::move(stream), SIZE_MAX),
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
  pipe_.start(shared_from_this());
  armTimer(context_.options.handshakeTimeout, "TLS handshake");
  pipe_.stream().open([self = shared_from_this()](const std::string& failure) {
    if (!failure.empty()) return self->close("TLS handshake failed: " + failure);
    self->waitForMessage();
    self->pipe_.read();
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
  if (pipe_.midMessage()) {
    close(greeted() ? "read timeout: a message was not finished" : "handshake timeout: no Hello");
  } else if (pending_ > 0) {
    armTimer(context_.options.idleTimeout, what);  // our own work is not idleness
  } else if (pipe_.writing()) {
    if (Clock::now() - pipe_.lastWrite() > context_.options.readTimeout) {
      close("client stopped reading its results");
    } else {
      armTimer(context_.options.readTimeout, what);
    }
  } else {
    close(std::string(what) + " timeout");
  }
}

std::size_t Connection::messageLimit() const {
  return greeted() ? context_.options.maxMessageBytes : ServerOptions::kMaxHandshakeMessageBytes;
}

void Connection::readFailed(const asio::error_code& error) {
  const bool mid = pipe_.midMessage();
  close(error == asio::error::eof ? (mid ? "disconnected mid-message" : "disconnected") : error.message());
}

void Connection::refused(const proto::Decoded& bad) {
  const bool tooLarge = bad.code == wire::ErrorCode::TooLarge;
  const std::string hint = greeted() ? " (is this a Glint client?)" : " before Hello (is this a Glint client?)";
  session_.error(bad.code, bad.error + (tooLarge ? hint : ""), true);
}

// After a read's messages (`wasMid`: part of a message was held before its
// bytes). A message started arms the read timeout once (before Hello the
// handshake's deadline stands: a header does not buy a connection more
// time); a connection between messages waits under the idle or handshake
// timeout.
void Connection::afterRead(bool wasMid, bool took) {
  const bool mid = pipe_.midMessage();
  if (mid && (took || !wasMid) && greeted()) armTimer(context_.options.readTimeout, "read");
  if (!mid && took) waitForMessage();
}

void Connection::waitForMessage() {
  armTimer(greeted() ? context_.options.idleTimeout : context_.options.handshakeTimeout,
           greeted() ? "idle" : "handshake");
}

void Connection::end(const std::string& why) {
  logLine(session_.peer() + ": " + why);
  closeAfterWrites_ = true;
  if (!pipe_.writing()) close(why);
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
  const std::size_t queued = pipe_.queuedBytes() + frame.size();
  if (queued > context_.options.maxQueuedBytes) {
    close("client is not reading its results (" + std::to_string(queued) + " bytes queued)");
    return;
  }
  pipe_.send(std::move(frame));  // everything queued goes out in one gathered write
}

void Connection::drained() {
  if (closeAfterWrites_) close("closed after its last reply");
}

void Connection::close(const std::string& why) {
  if (closed_) return;
  closed_ = true;
  context_.registry.remove(id_);
  const std::size_t dropped = context_.scheduler.cancel(id_);
  pending_ -= static_cast<int>(dropped);
  timer_.cancel();
  pipe_.stream().close();
  logLine(session_.peer() + ": closed (" + why +
          (dropped ? ", " + std::to_string(dropped) + " queued tiles cancelled" : "") + ")");
}

}  // namespace glint::server
