#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/base/memory_gauge.h"
#include "common/render/field_probes.h"
#include "common/render/irradiance_field.h"
#include "common/render/renderer.h"
#include "common/render/tile.h"
#include "proto/framing.h"
#include "proto/messages.h"
#include "server/scene_builder.h"
#include "server/scene_cache.h"

namespace glint::server {

// A frame set up by a client: the scene it renders and its renderer, with
// the irradiance field it reads (FrameSetup.field); or, for a frame that
// fills a field (fill_field), where the probes lie and their tracer.
struct SessionFrame {
  std::shared_ptr<const PreparedScene> scene;
  std::unique_ptr<Renderer> renderer;
  std::shared_ptr<const IrradianceField> field;
  std::unique_ptr<FieldGrid> grid;
  std::unique_ptr<ProbeTracer> probes;
};

// One tile to trace on the pool; the result is an encoded TileResult.
struct TileWork {
  std::shared_ptr<const SessionFrame> frame;
  TileRect rect;
  std::vector<std::uint8_t> mask;  // empty: every pixel
  std::uint32_t frameId = 0;
  std::uint32_t tileId = 0;
};
std::vector<std::uint8_t> traceTile(const TileWork& work);

// What a session needs from whatever carries it: a connection on a socket,
// or a test or fuzzer with byte vectors.
class SessionHost {
 public:
  virtual ~SessionHost() = default;
  virtual void reply(std::vector<std::uint8_t> frame) = 0;
  // No more messages will be taken: close once the replies are written.
  virtual void end(const std::string& why) = 0;
  // A Hello asks for a client's place; false when the server is full.
  virtual bool admit() = 0;
  // The client asked for work (an upload, a frame, a tile): it keeps its
  // place (ConnectionRegistry).
  virtual void worked() = 0;
  // Work for the pool; the build's result comes back to sceneBuilt().
  virtual void build(SceneJob job) = 0;
  virtual void trace(TileWork work) = 0;
  // Drops queued tiles of frame `frameId` (all of them when `tileIds` is
  // empty); tiles already being traced are still answered.
  virtual void cancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds) = 0;
};

// What the sessions of a server share: built scenes, uploaded files, and
// the memory that files still arriving draw from (given back when a file is
// complete or its session ends).
struct SessionStores {
  SceneCache& scenes;
  FileStore& files;
  MemoryGauge& uploads;
};

// The protocol state of one client, without a socket: it takes verified
// messages in order and answers through its host. Any value a client sent is
// checked before use; a problem is an Error to the client, and where the
// session cannot go on (not Hello first, wrong version, server full), the end.
class Session {
 public:
  enum class State { kAwaitingHello, kServing, kEnded };

  struct Settings {
    std::uint32_t maxMessageBytes = 0;  // announced in Hello
    std::uint32_t threads = 0;          // announced in Hello
    std::size_t maxClients = 0;         // named when a Hello finds the server full
    std::size_t maxFileBytes = 0;       // one uploaded file (--max-scene-mb)
  };

  Session(SessionHost& host, const SessionStores& stores, const Settings& settings, std::string peer);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  State state() const { return state_; }
  const std::string& peer() const { return peer_; }
  void handle(const wire::Message& message);
  // A build asked for through SessionHost::build is done.
  void sceneBuilt(const BuiltScene& built);
  // Sends an Error; with `final`, the session ends after it.
  void error(wire::ErrorCode code, const std::string& message, bool final, std::uint32_t frameId = 0,
             std::uint32_t tileId = 0);

 private:
  void dispatch(const wire::Message& message);
  void onHello(const wire::Hello& hello);
  void onSceneQuery(const wire::SceneQuery& query);
  void onSceneUpload(const wire::SceneUpload& upload);
  void onFileChunk(const wire::FileChunk& chunk);
  void dropPartial(const proto::SceneHash& hash);
  void onFrameSetup(const wire::FrameSetup& setup);
  void onTileRequest(const wire::TileRequest& tile);
  void onCancel(const wire::Cancel& cancel);
  void onFieldPiece(const wire::FieldPiece& piece);
  void dropField();
  // The frame's renderer, reading the connection's field where the frame names one.
  void setUpPixels(SessionFrame& frame, const FrameSettings& settings, const proto::FrameWork& work,
                   const proto::SceneHash& hash);

  // A file whose pieces are still arriving (FileChunk).
  struct PartialFile {
    std::uint64_t size = 0;
    std::string bytes;      // grows as pieces arrive, never ahead of them
    std::size_t taken = 0;  // from stores_.uploads
  };

  SessionHost& host_;
  SessionStores stores_;
  Settings settings_;
  std::string peer_;
  State state_ = State::kAwaitingHello;
  bool building_ = false;  // a SceneUpload of this client is being built: one at a time
  std::map<std::uint32_t, std::shared_ptr<const SessionFrame>> frames_;  // by frame id
  std::map<proto::SceneHash, PartialFile> partial_;  // given back to stores_.uploads when dropped
  // The irradiance field the client sent (FieldPiece), whole once every
  // probe came; its memory drawn from stores_.uploads while the session holds it.
  struct ReceivedField {
    proto::SceneHash scene{};
    std::shared_ptr<IrradianceField> field;
    int received = 0;       // probes so far
    std::size_t taken = 0;  // from stores_.uploads
    bool whole() const { return field && received == field->probeCount(); }
  };
  ReceivedField field_;
};

}  // namespace glint::server
