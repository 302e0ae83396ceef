#include "server/connection.h"

#include <unordered_set>

#include "common/base/timing.h"
#include "proto/tls.h"
#include "server/log.h"

namespace glint::server {
namespace {

constexpr std::size_t kReadChunkBytes = 64 * 1024;  // a message buffer's first size, and what an idle one keeps

std::string peerName(const asio::ip::tcp::socket::lowest_layer_type& socket, std::uint64_t id) {
  asio::error_code ec;
  const auto remote = socket.remote_endpoint(ec);
  return ec ? "client " + std::to_string(id) : remote.address().to_string() + ":" + std::to_string(remote.port());
}

// A tile's name in the scheduler's queue, for Cancel.
std::uint64_t tileTag(std::uint32_t frameId, std::uint32_t tileId) {
  return std::uint64_t{frameId} << 32 | tileId;
}

Session::Settings sessionSettings(const ServerContext& context) {
  return {static_cast<std::uint32_t>(context.options.maxMessageBytes),
          static_cast<std::uint32_t>(context.scheduler.threads()),
          static_cast<std::size_t>(context.options.maxClients), context.options.maxSceneBytes};
}

}  // namespace

template <typename Stream>
BasicConnection<Stream>::BasicConnection(Stream stream, ServerContext& context, std::uint64_t id)
    : socket_(std::move(stream)),
      timer_(context.io),
      context_(context),
      id_(id),
      outbox_(context.scheduler.threads()),
      session_(*this, {context.cache, context.files, context.buildMemory}, sessionSettings(context),
               peerName(socket_.lowest_layer(), id)) {
  asio::error_code ignored;
  socket_.lowest_layer().set_option(asio::ip::tcp::no_delay(true), ignored);
}

template <typename Stream>
void BasicConnection<Stream>::start() {
  logLine(session_.peer() + ": connected");
  if constexpr (std::is_same_v<Stream, TlsStream>) {
    handshake();
  } else {
    readHeader();
  }
}

// Before Hello comes the TLS handshake, under the same timeout and in the
// same waiting pool: a peer that starts one and stalls holds little, briefly.
template <typename Stream>
void BasicConnection<Stream>::handshake() {
  if constexpr (std::is_same_v<Stream, TlsStream>) {
    armTimer(context_.options.handshakeTimeout, "TLS handshake");
    socket_.async_handshake(asio::ssl::stream_base::server,
                            [self = this->shared_from_this()](const asio::error_code& e) {
                              if (!e) {
                                self->readHeader();
                                return;
                              }
                              const long verify = SSL_get_verify_result(self->socket_.native_handle());
                              self->close("TLS handshake failed: " + proto::describeTlsFailure(e, verify, false));
                            });
  }
}

template <typename Stream>
void BasicConnection<Stream>::armTimer(std::chrono::milliseconds timeout, const char* what) {
  timer_.expires_after(timeout);
  timer_.async_wait([self = this->shared_from_this(), what](const asio::error_code& error) {
    if (!error && !self->closed_) self->onTimer(what);  // else re-armed or closed
  });
}

// What a silent client holds is freed: a message started and not finished,
// a connection with nothing to do, a client that stopped reading its results.
template <typename Stream>
void BasicConnection<Stream>::onTimer(const char* what) {
  if (midMessage_) {
    close(greeted() ? "read timeout: a message was not finished" : "handshake timeout: no Hello");
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

template <typename Stream>
void BasicConnection<Stream>::readHeader() {
  if (closed_ || closeAfterWrites_) return;
  armTimer(greeted() ? context_.options.idleTimeout : context_.options.handshakeTimeout,
           greeted() ? "idle" : "handshake");
  asio::async_read(socket_, asio::buffer(header_),
                   [self = this->shared_from_this()](const asio::error_code& error, std::size_t) {
                     if (error) {
                       self->close(error == asio::error::eof ? "disconnected" : error.message());
                       return;
                     }
                     const std::uint32_t length = proto::frameLength(self->header_);
                     const bool greeted = self->greeted();
                     const std::size_t limit = greeted ? self->context_.options.maxMessageBytes
                                                       : ServerOptions::kMaxHandshakeMessageBytes;
                     if (length > limit) {
                       self->session_.error(wire::ErrorCode::TooLarge,
                                            "message of " + std::to_string(length) + " bytes is over the limit of " +
                                                std::to_string(limit) + (greeted ? "" : " before Hello") +
                                                " (is this a Glint client?)",
                                            true);
                       return;
                     }
                     self->readBody(length);
                   });
}

template <typename Stream>
void BasicConnection<Stream>::readBody(std::uint32_t length) {
  midMessage_ = true;
  // Before Hello the handshake's deadline stands: a header does not buy a
  // connection the read timeout.
  if (greeted()) armTimer(context_.options.readTimeout, "read");
  body_.clear();
  readMore(length);
}

// Memory follows the bytes that arrive, not the length a header announces:
// the buffer grows by at most what it already holds (kReadChunkBytes to
// start), so a peer that announces 64 MiB and sends 4 bytes costs 64 KiB.
template <typename Stream>
void BasicConnection<Stream>::readMore(std::uint32_t length) {
  const std::size_t have = body_.size();
  const std::size_t step = std::min<std::size_t>(length - have, std::max(kReadChunkBytes, have));
  body_.resize(have + step);
  asio::async_read(socket_, asio::buffer(body_.data() + have, step),
                   [self = this->shared_from_this(), length](const asio::error_code& error, std::size_t) {
                     if (error) {
                       self->close(error == asio::error::eof ? "disconnected mid-message" : error.message());
                     } else if (self->body_.size() < length) {
                       self->readMore(length);
                     } else {
                       self->onBody();
                     }
                   });
}

template <typename Stream>
void BasicConnection<Stream>::onBody() {
  midMessage_ = false;
  std::string problem;
  const wire::Message* message = proto::verifyMessage(body_, &problem);
  if (message) {
    session_.handle(*message);
  } else {
    session_.error(wire::ErrorCode::Malformed, problem, true);
  }
  // What a message needs is copied out by the session: a large buffer is not
  // kept for an idle connection.
  if (body_.capacity() > kReadChunkBytes) std::vector<std::uint8_t>().swap(body_);
  readHeader();
}

template <typename Stream>
void BasicConnection<Stream>::end(const std::string& why) {
  logLine(session_.peer() + ": " + why);
  closeAfterWrites_ = true;
  if (!writing_) close(why);
}

template <typename Stream>
bool BasicConnection<Stream>::admit() { return context_.registry.admit(id_); }

template <typename Stream>
void BasicConnection<Stream>::worked() { context_.registry.worked(id_); }

template <typename Stream>
void BasicConnection<Stream>::build(SceneJob job) {
  ++pending_;
  context_.builds.build(std::move(job), [self = this->shared_from_this()](const BuiltScene& built) {
    asio::post(self->context_.io, [self, built] {
      --self->pending_;
      if (!self->closed_) self->session_.sceneBuilt(built);
    });
  });
}

template <typename Stream>
void BasicConnection<Stream>::trace(TileWork work) {
  ++pending_;
  outbox_.expect();
  const std::uint64_t tag = tileTag(work.frameId, work.tileId);
  context_.scheduler.submit(
      id_,
      [self = this->shared_from_this(), work = std::move(work)] {
        if (self->outbox_.put(traceTile(work))) asio::post(self->context_.io, [self] { self->takeOutbox(); });
      },
      tag);
}

template <typename Stream>
void BasicConnection<Stream>::cancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds) {
  const std::unordered_set<std::uint32_t> tiles(tileIds.begin(), tileIds.end());
  const std::size_t dropped = context_.scheduler.cancel(id_, [&](std::uint64_t tag) {
    return tag >> 32 == frameId && (tiles.empty() || tiles.contains(static_cast<std::uint32_t>(tag)));
  });
  if (dropped == 0) return;
  pending_ -= static_cast<int>(dropped);
  if (outbox_.forget(dropped)) takeOutbox();
}

template <typename Stream>
void BasicConnection<Stream>::takeOutbox() {
  std::vector<std::vector<std::uint8_t>> results = outbox_.take();
  pending_ -= static_cast<int>(results.size());
  for (auto& r : results) reply(std::move(r));
}

template <typename Stream>
void BasicConnection<Stream>::reply(std::vector<std::uint8_t> frame) {
  if (closed_) return;
  queuedBytes_ += frame.size();
  if (queuedBytes_ > context_.options.maxQueuedBytes) {
    close("client is not reading its results (" + std::to_string(queuedBytes_) + " bytes queued)");
    return;
  }
  writes_.push_back(std::move(frame));
  if (!writing_) writeNext();
}

template <typename Stream>
void BasicConnection<Stream>::writeNext() {
  if (writes_.empty() || closed_) {
    writing_ = false;
    if (closeAfterWrites_) close("closed after its last reply");
    return;
  }
  // Everything queued goes out in one gathered write (one system call for
  // many small tile results); new results queue up behind it.
  writing_ = true;
  lastWrite_ = Clock::now();
  inFlight_ = writes_.size();
  std::vector<asio::const_buffer> buffers;
  if constexpr (std::is_same_v<Stream, TlsStream>) {
    // A TLS stream writes one buffer at a time (a record and a system call
    // each): the messages are joined first.
    flat_.clear();
    for (const auto& frame : writes_) flat_.insert(flat_.end(), frame.begin(), frame.end());
    buffers.push_back(asio::buffer(flat_));
  } else {
    buffers.reserve(inFlight_);
    for (const auto& frame : writes_) buffers.push_back(asio::buffer(frame));
  }
  asio::async_write(socket_, buffers, [self = this->shared_from_this()](const asio::error_code& error, std::size_t) {
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

template <typename Stream>
void BasicConnection<Stream>::close(const std::string& why) {
  if (closed_) return;
  closed_ = true;
  context_.registry.remove(id_);
  const std::size_t dropped = context_.scheduler.cancel(id_);
  pending_ -= static_cast<int>(dropped);
  asio::error_code ignored;
  timer_.cancel();
  socket_.lowest_layer().shutdown(asio::ip::tcp::socket::shutdown_both, ignored);
  socket_.lowest_layer().close(ignored);
  logLine(session_.peer() + ": closed (" + why + (dropped ? ", " + std::to_string(dropped) + " queued tiles cancelled" : "") +
          ")");
}

template class BasicConnection<asio::ip::tcp::socket>;
template class BasicConnection<TlsStream>;

}  // namespace glint::server
