#include "server/connection.h"

#include <chrono>

#include "common/error.h"
#include "proto/messages.h"
#include "server/log.h"

namespace glint::server {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kMaxFramesPerClient = 16;  // older frames are forgotten
constexpr std::size_t kReadChunkBytes = 64 * 1024;  // a message buffer's first size, and what an idle one keeps

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

Connection::Connection(asio::ip::tcp::socket socket, ServerContext& context, std::uint64_t id)
    : socket_(std::move(socket)), timer_(context.io), context_(context), id_(id) {
  asio::error_code ec;
  const auto remote = socket_.remote_endpoint(ec);
  peer_ = ec ? "client " + std::to_string(id) : remote.address().to_string() + ":" + std::to_string(remote.port());
  socket_.set_option(asio::ip::tcp::no_delay(true), ec);
}

void Connection::start() {
  logLine(peer_ + ": connected");
  readHeader();
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
  if (midMessage_) {
    close("read timeout: a message was not finished");
  } else if (pending_ > 0) {
    armTimer(context_.options.idleTimeout, what);  // our own work is not idleness
  } else if (writing_) {
    if (Clock::now() - lastWrite_ > context_.options.readTimeout) {
      close("client stopped reading its results");
    } else {
      armTimer(context_.options.readTimeout, what);
    }
  } else {
    close(std::string(what) + " timeout");
  }
}

void Connection::readHeader() {
  if (closed_ || closeAfterWrites_) return;
  armTimer(greeted_ ? context_.options.idleTimeout : context_.options.handshakeTimeout,
           greeted_ ? "idle" : "handshake");
  asio::async_read(socket_, asio::buffer(header_),
                   [self = shared_from_this()](const asio::error_code& error, std::size_t) {
                     if (error) {
                       self->close(error == asio::error::eof ? "disconnected" : error.message());
                       return;
                     }
                     const std::uint32_t length = proto::frameLength(self->header_);
                     const std::size_t limit = self->greeted_ ? self->context_.options.maxMessageBytes
                                                              : ServerOptions::kMaxHandshakeMessageBytes;
                     if (length > limit) {
                       self->fail(wire::ErrorCode::TooLarge,
                                  "message of " + std::to_string(length) + " bytes is over the limit of " +
                                      std::to_string(limit) + (self->greeted_ ? "" : " before Hello") +
                                      " (is this a Glint client?)");
                       return;
                     }
                     self->readBody(length);
                   });
}

void Connection::readBody(std::uint32_t length) {
  midMessage_ = true;
  armTimer(context_.options.readTimeout, "read");
  body_.clear();
  readMore(length);
}

// Memory follows the bytes that arrive, not the length a header announces:
// the buffer grows by at most what it already holds (kReadChunkBytes to
// start), so a peer that announces 64 MiB and sends 4 bytes costs 64 KiB.
void Connection::readMore(std::uint32_t length) {
  const std::size_t have = body_.size();
  const std::size_t step = std::min<std::size_t>(length - have, std::max(kReadChunkBytes, have));
  body_.resize(have + step);
  asio::async_read(socket_, asio::buffer(body_.data() + have, step),
                   [self = shared_from_this(), length](const asio::error_code& error, std::size_t) {
                     if (error) {
                       self->close(error == asio::error::eof ? "disconnected mid-message" : error.message());
                     } else if (self->body_.size() < length) {
                       self->readMore(length);
                     } else {
                       self->onBody();
                     }
                   });
}

void Connection::onBody() {
  midMessage_ = false;
  std::string problem;
  const wire::Message* message = proto::verifyMessage(body_, &problem);
  if (!message) {
    fail(wire::ErrorCode::Malformed, problem);
    return;
  }
  try {
    handle(*message);
  } catch (const InputError& e) {
    sendError(wire::ErrorCode::Malformed, e.what());
  }
  // What a message needs is copied out by its handler: a large buffer is not
  // kept for an idle connection.
  if (body_.capacity() > kReadChunkBytes) std::vector<std::uint8_t>().swap(body_);
  readHeader();
}

void Connection::handle(const wire::Message& m) {
  if (!greeted_ && m.body_type() != wire::Body::Hello) {
    fail(wire::ErrorCode::UnknownMessage, std::string("expected Hello first, got ") + proto::bodyName(m.body_type()));
    return;
  }
  switch (m.body_type()) {
    case wire::Body::Hello:
      return onHello(*m.body_as_Hello());
    case wire::Body::SceneQuery:
      return onSceneQuery(*m.body_as_SceneQuery());
    case wire::Body::SceneUpload:
      return onSceneUpload(*m.body_as_SceneUpload());
    case wire::Body::FrameSetup:
      return onFrameSetup(*m.body_as_FrameSetup());
    case wire::Body::TileRequest:
      return onTileRequest(*m.body_as_TileRequest());
    case wire::Body::Goodbye:
      logLine(peer_ + ": goodbye");
      closeAfterWrites_ = true;
      if (!writing_) close("goodbye");
      return;
    default:
      sendError(wire::ErrorCode::UnknownMessage,
                std::string("a server does not take ") + proto::bodyName(m.body_type()) + " messages");
  }
}

void Connection::onHello(const wire::Hello& hello) {
  if (hello.protocol_version() != proto::kProtocolVersion) {
    fail(wire::ErrorCode::Version, "protocol version " + std::to_string(hello.protocol_version()) +
                                       " is not spoken here (this server speaks " +
                                       std::to_string(proto::kProtocolVersion) + ")");
    return;
  }
  if (!context_.registry.admit(id_)) {
    fail(wire::ErrorCode::Busy, "the server has its maximum of " + std::to_string(context_.registry.maxClients()) +
                                    " clients; try later");
    return;
  }
  greeted_ = true;
  send(proto::encodeHello(static_cast<std::uint32_t>(context_.options.maxMessageBytes),
                          static_cast<std::uint32_t>(context_.scheduler.threads()), "glintd 0.1"));
}

void Connection::onSceneQuery(const wire::SceneQuery& query) {
  const proto::SceneHash hash = proto::decodeHash(query.hash(), "scene_query.hash");
  send(proto::encodeSceneStatus(hash, context_.cache.find(hash) != nullptr));
}

void Connection::onSceneUpload(const wire::SceneUpload& upload) {
  const proto::SceneHash hash = proto::decodeHash(upload.hash(), "scene_upload.hash");
  // Copy the bytes out of the read buffer, which the next message reuses.
  auto bundle = std::make_shared<proto::SceneBundle>(proto::decodeBundle(upload));
  ++pending_;
  context_.scheduler.submit(id_, [self = shared_from_this(), hash, bundle] {
    const Clock::time_point start = Clock::now();
    std::shared_ptr<const PreparedScene> prepared;
    std::string error;
    try {
      if (bundle->hash() != hash) throw InputError("the scene's bytes do not match its hash");
      LoadLimits limits;
      limits.maxSceneBytes = self->context_.options.maxSceneBytes;
      // Held through the BVH build: what the scene will hold counts against
      // the server's memory until the cache takes it.
      SceneBudget budget(limits, "glintd --max-scene-mb", &self->context_.buildMemory);
      prepared = std::make_shared<const PreparedScene>(proto::loadBundle(*bundle, budget), BvhSettings{});
    } catch (const InputError& e) {
      error = e.what();
    } catch (const std::exception& e) {
      error = std::string("cannot load the scene: ") + e.what();
    }
    const double ms = msSince(start);
    asio::post(self->context_.io, [self, hash, prepared, error, ms] {
      --self->pending_;
      if (self->closed_) return;
      if (!prepared) {
        logLine(self->peer_ + ": scene " + proto::toHex(hash).substr(0, 12) + " rejected: " + error);
        self->sendError(wire::ErrorCode::BadScene, error);
        return;
      }
      self->context_.cache.insert(hash, prepared);
      logLine(self->peer_ + ": scene " + proto::toHex(hash).substr(0, 12) + " built in " + std::to_string(ms) +
              " ms (" + std::to_string(prepared->scene().geometry.primitiveCount()) + " primitives)");
      self->send(proto::encodeSceneReady(hash, static_cast<float>(ms)));
    });
  });
}

void Connection::onFrameSetup(const wire::FrameSetup& setup) {
  const std::uint32_t frameId = setup.frame_id();
  try {
    const proto::SceneHash hash = proto::decodeHash(setup.scene_hash(), "frame_setup.scene_hash");
    auto scene = context_.cache.find(hash);
    if (!scene) {
      sendError(wire::ErrorCode::UnknownScene, "scene " + proto::toHex(hash).substr(0, 12) +
                                                   " is not on this server; upload it first", frameId);
      return;
    }
    const FrameSettings settings = proto::decodeFrameSettings(setup, LoadLimits{}.maxImagePixels);
    auto frame = std::make_shared<Frame>();
    frame->renderer = std::make_unique<Renderer>(*scene, settings);
    frame->scene = std::move(scene);
    frames_[frameId] = std::move(frame);
    while (frames_.size() > kMaxFramesPerClient) frames_.erase(frames_.begin());
  } catch (const InputError& e) {
    sendError(wire::ErrorCode::BadFrame, e.what(), frameId);
  }
}

void Connection::onTileRequest(const wire::TileRequest& request) {
  const std::uint32_t frameId = request.frame_id();
  const std::uint32_t tileId = request.tile_id();
  const auto it = frames_.find(frameId);
  if (it == frames_.end()) {
    sendError(wire::ErrorCode::UnknownFrame, "tile " + std::to_string(tileId) + " is for frame " +
                                                 std::to_string(frameId) + ", which was never set up",
              frameId, tileId);
    return;
  }
  TileRect rect;
  try {
    rect = proto::decodeTileRect(request, it->second->renderer->frame());
  } catch (const InputError& e) {
    sendError(wire::ErrorCode::BadTile, e.what(), frameId, tileId);
    return;
  }
  std::vector<std::uint8_t> mask;
  if (request.mask()) mask.assign(request.mask()->begin(), request.mask()->end());
  ++pending_;
  {
    std::lock_guard lock(outboxMutex_);
    ++untraced_;
  }
  context_.scheduler.submit(id_, [self = shared_from_this(), frame = it->second, rect, mask = std::move(mask),
                                  frameId, tileId] {
    const Clock::time_point start = Clock::now();
    std::vector<std::uint8_t> rgb;
    RayStats rays;
    frame->renderer->renderTile(rect, mask, rgb, rays);
    const auto micros = static_cast<std::uint32_t>(msSince(start) * 1000.0);
    std::vector<std::uint8_t> result = proto::encodeTileResult(frameId, tileId, rgb, rays, micros);
    self->deliver(std::move(result));
  });
}

// Called on pool threads. Results wait in the outbox until it holds
// kFlushBytes or the client's last submitted tile is done; then one wake-up
// of the I/O thread takes them all into one gathered write. Each wake-up
// preempts a tracing thread where client and server share the cores, so a
// frame's 80 results go out in about 23 writes instead of about 65.
void Connection::deliver(std::vector<std::uint8_t> result) {
  constexpr std::size_t kFlushBytes = 128 * 1024;  // 64 KiB: 2.1 ms overhead per frame, 128 KiB: 1.0-1.4
  bool wake = false;
  {
    std::lock_guard lock(outboxMutex_);
    outboxBytes_ += result.size();
    outbox_.push_back(std::move(result));
    --untraced_;
    wake = !wakePosted_ && (untraced_ == 0 || outboxBytes_ >= kFlushBytes);
    wakePosted_ = wakePosted_ || wake;
  }
  if (!wake) return;
  asio::post(context_.io, [self = shared_from_this()] {
    std::vector<std::vector<std::uint8_t>> results;
    {
      std::lock_guard lock(self->outboxMutex_);
      results.swap(self->outbox_);
      self->outboxBytes_ = 0;
      self->wakePosted_ = false;
    }
    self->pending_ -= static_cast<int>(results.size());
    for (auto& r : results) self->send(std::move(r));
  });
}

void Connection::send(std::vector<std::uint8_t> frame) {
  if (closed_) return;
  queuedBytes_ += frame.size();
  if (queuedBytes_ > context_.options.maxQueuedBytes) {
    close("client is not reading its results (" + std::to_string(queuedBytes_) + " bytes queued)");
    return;
  }
  writes_.push_back(std::move(frame));
  if (!writing_) writeNext();
}

void Connection::sendError(wire::ErrorCode code, const std::string& message, std::uint32_t frameId,
                           std::uint32_t tileId) {
  logLine(peer_ + ": error " + wire::EnumNameErrorCode(code) + ": " + message);
  send(proto::encodeError(code, message, frameId, tileId));
}

void Connection::fail(wire::ErrorCode code, const std::string& message) {
  sendError(code, message);
  closeAfterWrites_ = true;
}

void Connection::writeNext() {
  if (writes_.empty() || closed_) {
    writing_ = false;
    if (closeAfterWrites_) close("closed after error");
    return;
  }
  // Everything queued goes out in one gathered write (one system call for
  // many small tile results); new results queue up behind it.
  writing_ = true;
  lastWrite_ = Clock::now();
  inFlight_ = writes_.size();
  std::vector<asio::const_buffer> buffers;
  buffers.reserve(inFlight_);
  for (const auto& frame : writes_) buffers.push_back(asio::buffer(frame));
  asio::async_write(socket_, buffers, [self = shared_from_this()](const asio::error_code& error, std::size_t) {
    if (error) {
      self->close(error.message());
      return;
    }
    for (std::size_t i = 0; i < self->inFlight_; ++i) {
      self->queuedBytes_ -= self->writes_.front().size();
      self->writes_.pop_front();
    }
    self->writeNext();
  });
}

void Connection::close(const std::string& why) {
  if (closed_) return;
  closed_ = true;
  context_.registry.remove(id_);
  const std::size_t dropped = context_.scheduler.cancel(id_);
  pending_ -= static_cast<int>(dropped);
  asio::error_code ignored;
  timer_.cancel();
  socket_.shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket_.close(ignored);
  frames_.clear();
  logLine(peer_ + ": closed (" + why + (dropped ? ", " + std::to_string(dropped) + " queued tiles cancelled" : "") +
          ")");
}

}  // namespace glint::server
