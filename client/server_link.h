#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <asio.hpp>

#include "client/link_stream.h"
#include "common/scene/scene.h"
#include "common/render/tile_service.h"
#include "proto/framing.h"
#include "proto/scene_bundle.h"

namespace glint {

// Why a server can no longer serve this client.
struct LinkFailure {
  enum class Kind {
    kUnreachable,  // cannot connect, or no answer to Hello in time
    kRefused,      // answered, but will not or must not serve us (busy, version, another build)
    kClosed,       // closed the connection
    kBadBytes,     // sent something that is not a valid answer
    kServerError,  // sent an Error about something other than the scene
    kSceneError,   // the scene failed to load there: the same on every server
    kStalled,      // tiles outstanding, nothing delivered for the stall timeout
  };
  Kind kind;
  std::string what;
};

class ServerLink;

// How long a link waits for the server before it counts as unreachable.
struct LinkTimeouts {
  std::chrono::milliseconds connect{5000};  // connect and Hello
  // The upload with no byte written for this long, or the server's build of
  // the scene after it (--scene-timeout).
  std::chrono::milliseconds scene{120000};
};

// What a link tells its owner, always on the thread running the I/O context.
class LinkListener {
 public:
  virtual ~LinkListener() = default;
  virtual void linkReady(ServerLink& link) = 0;
  virtual void linkResult(ServerLink& link, std::uint32_t frameId, std::uint32_t tileId, TileOutput&& out) = 0;
  virtual void linkFailed(ServerLink& link, const LinkFailure& failure) = 0;
};

// One glintd seen from the client: connects, says Hello (refusing a server
// of another build), makes sure the server holds the scene (uploading it
// only when it does not), then carries frames, tile requests and cancels out
// and tile results in, pipelined. Every message from the server is verified
// and checked against what was asked of it; anything else fails the link.
// Asynchronous on an io_context shared with the other links; owned through a
// shared_ptr so that handlers in flight outlive a link its owner dropped.
class ServerLink : public std::enable_shared_from_this<ServerLink> {
 public:
  // `stream` is plain TCP or TLS (client/link_stream.h).
  ServerLink(asio::io_context& io, std::unique_ptr<LinkStream> stream, std::size_t index, std::string name,
             const asio::ip::tcp::endpoint& endpoint, const proto::SceneBundle& bundle,
             const proto::BundleDigest& digest, const LinkTimeouts& timeouts);
  ServerLink(const ServerLink&) = delete;
  ServerLink& operator=(const ServerLink&) = delete;

  void start(LinkListener& listener);
  // Stops telling the listener anything, and closes.
  void detach();

  void setupFrame(std::uint32_t frameId, const FrameSettings& frame);
  void request(std::uint32_t frameId, std::uint32_t tileId, const TileJob& job);
  void cancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds);
  // Fails the link from outside (the dispatcher found it stalled).
  void fail(LinkFailure::Kind kind, const std::string& what);
  // Says Goodbye and closes once it is written.
  void close();

  std::size_t index() const { return index_; }
  const std::string& name() const { return name_; }
  bool ready() const { return state_ == State::kReady; }
  bool failed() const { return state_ == State::kFailed; }
  int threads() const { return threads_; }
  bool uploaded() const { return uploaded_; }
  std::uint64_t bytesSent() const { return sent_; }
  std::uint64_t bytesReceived() const { return received_; }

 private:
  enum class State { kConnecting, kHello, kQuery, kUpload, kReady, kFailed, kClosed };

  void onConnected(const std::string& failure);
  void armTimer(std::chrono::milliseconds timeout, const char* waitingFor);
  void write(std::vector<std::uint8_t> frame);
  void writeNext();
  void readMore();
  void onRead(const asio::error_code& error, std::size_t n);
  void onMessage(const wire::Message& m);
  void onHello(const wire::Hello& hello);
  void onSceneStatus(const wire::SceneStatus& status);
  bool sendMissingFiles(const wire::SceneStatus& status);
  void onResult(const wire::TileResult& result);
  void onError(const wire::Error& error);
  void becomeReady();

  std::unique_ptr<LinkStream> stream_;
  asio::steady_timer timer_;
  std::size_t index_;
  std::string name_;
  asio::ip::tcp::endpoint endpoint_;
  const proto::SceneBundle& bundle_;
  const proto::BundleDigest& digest_;  // the scene's hash and its files', computed once for every server
  LinkTimeouts timeouts_;
  LinkListener* listener_ = nullptr;
  State state_ = State::kConnecting;
  std::size_t maxMessageBytes_ = proto::kDefaultMaxMessageBytes;
  int threads_ = 1;
  bool uploaded_ = false;
  std::map<std::uint64_t, std::size_t> pending_;  // (frame, tile) asked for -> pixel bytes of its result
  std::deque<std::vector<std::uint8_t>> writes_;
  std::size_t inFlight_ = 0;  // messages of writes_ in the current write
  std::vector<std::uint8_t> buffer_;  // received, not yet decoded
  std::vector<std::uint64_t> aligned_;
  std::uint64_t sent_ = 0;
  std::uint64_t received_ = 0;
};

}  // namespace glint
