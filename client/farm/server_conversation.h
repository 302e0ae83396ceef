#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/render/tile_service.h"
#include "common/scene/scene.h"
#include "proto/framing.h"
#include "proto/messages.h"
#include "proto/scene_bundle.h"

namespace glint {

// Why a server can no longer serve this client.
struct LinkFailure {
  enum class Kind {
    kUnreachable,  // cannot connect, or no answer in time
    kBusy,         // answered Busy before serving us (full of clients, or of scenes being built): tried again
    kRefused,      // answered, but will not or must not serve us (version, another build)
    kClosed,       // closed the connection
    kBadBytes,     // sent something that is not a valid answer
    kServerError,  // sent an Error about something other than the scene
    kSceneError,   // the scene failed to load there: the same on every server
    kStalled,      // tiles outstanding, nothing delivered for the stall timeout
  };
  Kind kind;
  std::string what;
};

// How long the client waits for a server before it counts as unreachable.
struct LinkTimeouts {
  std::chrono::milliseconds connect{5000};  // connect and Hello
  // The upload with no byte written for this long, or the server's build of
  // the scene after it (--scene-timeout).
  std::chrono::milliseconds scene{120000};
};

// What a conversation needs from whatever carries it: a ServerLink on a
// socket, or a test or fuzzer with byte vectors and a clock of its own.
class ConversationHost {
 public:
  virtual ~ConversationHost() = default;
  virtual void send(std::vector<std::uint8_t> frame) = 0;
  // (Re)starts the one wait: timedOut() is due if nothing stops it first.
  virtual void await(std::chrono::milliseconds timeout) = 0;
  virtual void stopWaiting() = 0;
  virtual void serving() = 0;
  virtual void delivered(std::uint32_t frameId, std::uint32_t tileId, TileOutput&& out) = 0;
  // The end: the conversation sends and takes nothing more.
  virtual void lost(const LinkFailure& failure) = 0;
};

// The client's side of the protocol with one glintd, without a socket (the
// twin of glintd's Session): Hello (refusing a server of another build),
// the scene query and, only where the server lacks the scene, its upload;
// then frames, tile requests and cancels out, tile results in. It takes
// verified messages in order; each is checked against what was asked of
// the server, and anything else fails the conversation.
class ServerConversation {
 public:
  enum class State { kConnecting, kHello, kQuery, kUpload, kReady, kFailed, kClosed };

  ServerConversation(ConversationHost& host, const proto::SceneBundle& bundle, const proto::BundleDigest& digest,
                     const LinkTimeouts& timeouts);

  // Inputs from the carrier: connecting, connected, ...
  void start();
  void connected();
  void handle(const wire::Message& message);
  // `bytes` of what was sent reached the stream: an upload still moving.
  void wrote(std::size_t bytes);
  // The wait asked for last ran out.
  void timedOut();
  // The stream ended or broke; `why` in words.
  void streamEnded(const std::string& why);
  void fail(LinkFailure::Kind kind, const std::string& what);

  // Inputs from the client.
  void setupFrame(std::uint32_t frameId, const FrameSettings& frame, const proto::FrameWork& work = {});
  // A job of a fill frame (FrameWork::fill) is a batch of probes: its
  // rectangle's x and width their first and count.
  void request(std::uint32_t frameId, std::uint32_t tileId, const TileJob& job);
  // The irradiance field the frames after read (FrameWork::field), in pieces.
  void sendField(const IrradianceField& field);
  void cancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds);
  // Says Goodbye; nothing more is taken.
  void close();

  State state() const { return state_; }
  bool over() const { return state_ == State::kFailed || state_ == State::kClosed; }
  int threads() const { return threads_; }
  bool uploaded() const { return uploaded_; }

 private:
  void await(std::chrono::milliseconds timeout, const char* waitingFor);
  void onHello(const wire::Hello& hello);
  void onSceneStatus(const wire::SceneStatus& status);
  bool sendMissingFiles(const wire::SceneStatus& status);
  void onResult(const wire::TileResult& result);
  void onError(const wire::Error& error);
  void becomeReady();

  ConversationHost& host_;
  const proto::SceneBundle& bundle_;
  const proto::BundleDigest& digest_;  // the scene's hash and its files', computed once for every server
  LinkTimeouts timeouts_;
  State state_ = State::kConnecting;
  std::chrono::milliseconds waited_{0};  // the wait asked for last, and for what
  const char* waitingFor_ = "";
  std::size_t maxMessageBytes_ = proto::kDefaultMaxMessageBytes;
  int threads_ = 1;
  bool uploaded_ = false;
  // What a result must carry: pixel bytes, or a batch's probe values.
  struct Expected {
    std::size_t rgb = 0;
    std::size_t probes = 0;
  };
  std::map<std::uint64_t, Expected> pending_;  // (frame, tile) asked for -> what its result carries
  std::optional<std::uint32_t> fillFrame_;      // the last frame set up, when it fills a field
};

}  // namespace glint
