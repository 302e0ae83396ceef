#include "server/session.h"

#include "common/error.h"
#include "common/frame_limits.h"
#include "common/timing.h"
#include "proto/messages.h"
#include "server/log.h"

namespace glint::server {
namespace {


std::string shortHash(const proto::SceneHash& hash) { return proto::toHex(hash).substr(0, 12); }

}  // namespace

std::vector<std::uint8_t> traceTile(const TileWork& work) {
  const auto start = Clock::now();
  std::vector<std::uint8_t> rgb;
  RayStats rays;
  work.frame->renderer->renderTile(work.rect, work.mask, rgb, rays);
  const auto micros = static_cast<std::uint32_t>(msSince(start) * 1000.0);
  return proto::encodeTileResult(work.frameId, work.tileId, rgb, rays, micros);
}

Session::Session(SessionHost& host, SceneCache& cache, const Settings& settings, std::string peer)
    : host_(host), cache_(cache), settings_(settings), peer_(std::move(peer)) {}

void Session::handle(const wire::Message& message) {
  if (state_ == State::kEnded) return;
  try {
    dispatch(message);
  } catch (const InputError& e) {
    error(wire::ErrorCode::Malformed, e.what(), false);
  }
}

void Session::dispatch(const wire::Message& m) {
  if (state_ == State::kAwaitingHello && m.body_type() != wire::Body::Hello) {
    error(wire::ErrorCode::UnknownMessage, std::string("expected Hello first, got ") + proto::bodyName(m.body_type()),
          true);
    return;
  }
  // verifyMessage guarantees that the body named is there.
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
    case wire::Body::Cancel:
      return onCancel(*m.body_as_Cancel());
    case wire::Body::Goodbye:
      state_ = State::kEnded;
      frames_.clear();
      host_.end("goodbye");
      return;
    default:
      error(wire::ErrorCode::UnknownMessage,
            std::string("a server does not take ") + proto::bodyName(m.body_type()) + " messages", false);
  }
}

void Session::error(wire::ErrorCode code, const std::string& message, bool final, std::uint32_t frameId,
                    std::uint32_t tileId) {
  if (state_ == State::kEnded) return;
  logLine(peer_ + ": error " + wire::EnumNameErrorCode(code) + ": " + message);
  host_.reply(proto::encodeError(code, message, frameId, tileId));
  if (final) {
    state_ = State::kEnded;
    frames_.clear();
    host_.end("closed after error");
  }
}

void Session::onHello(const wire::Hello& hello) {
  if (state_ != State::kAwaitingHello) {
    error(wire::ErrorCode::UnknownMessage, "a second Hello", false);
    return;
  }
  if (hello.protocol_version() != proto::kProtocolVersion) {
    error(wire::ErrorCode::Version,
          "protocol version " + std::to_string(hello.protocol_version()) + " is not spoken here (this server speaks " +
              std::to_string(proto::kProtocolVersion) + ")",
          true);
    return;
  }
  if (!host_.admit()) {
    error(wire::ErrorCode::Busy,
          "the server has its maximum of " + std::to_string(settings_.maxClients) + " clients; try later", true);
    return;
  }
  state_ = State::kServing;
  host_.reply(proto::encodeHello(settings_.maxMessageBytes, settings_.threads, "glintd 0.1"));
}

void Session::onSceneQuery(const wire::SceneQuery& query) {
  const proto::SceneHash hash = proto::decodeHash(query.hash(), "scene_query.hash");
  host_.reply(proto::encodeSceneStatus(hash, cache_.find(hash) != nullptr));
}

void Session::onSceneUpload(const wire::SceneUpload& upload) {
  const proto::SceneHash hash = proto::decodeHash(upload.hash(), "scene_upload.hash");
  // Copied out of the read buffer, which the next message reuses.
  host_.build({hash, std::make_shared<const proto::SceneBundle>(proto::decodeBundle(upload))});
}

void Session::sceneBuilt(const BuiltScene& built) {
  if (state_ == State::kEnded) return;
  if (!built.prepared) {
    logLine(peer_ + ": scene " + shortHash(built.hash) + " rejected");
    error(wire::ErrorCode::BadScene, built.error, false);
    return;
  }
  cache_.insert(built.hash, built.prepared);
  logLine(peer_ + ": scene " + shortHash(built.hash) + " built in " + std::to_string(built.ms) + " ms (" +
          std::to_string(built.prepared->scene().geometry.primitiveCount()) + " primitives)");
  host_.reply(proto::encodeSceneReady(built.hash, static_cast<float>(built.ms)));
}

void Session::onFrameSetup(const wire::FrameSetup& setup) {
  const std::uint32_t frameId = setup.frame_id();
  try {
    const proto::SceneHash hash = proto::decodeHash(setup.scene_hash(), "frame_setup.scene_hash");
    auto scene = cache_.find(hash);
    if (!scene) {
      error(wire::ErrorCode::UnknownScene, "scene " + shortHash(hash) + " is not on this server; upload it first",
            false, frameId);
      return;
    }
    const FrameSettings settings = proto::decodeFrameSettings(setup, FrameLimits::kMaxPixels);
    auto frame = std::make_shared<SessionFrame>();
    frame->renderer = std::make_unique<Renderer>(*scene, settings);
    frame->scene = std::move(scene);
    frames_[frameId] = std::move(frame);
    while (frames_.size() > proto::kFramesRemembered) frames_.erase(frames_.begin());
  } catch (const InputError& e) {
    error(wire::ErrorCode::BadFrame, e.what(), false, frameId);
  }
}

void Session::onTileRequest(const wire::TileRequest& request) {
  const std::uint32_t frameId = request.frame_id();
  const std::uint32_t tileId = request.tile_id();
  const auto it = frames_.find(frameId);
  if (it == frames_.end()) {
    error(wire::ErrorCode::UnknownFrame,
          "tile " + std::to_string(tileId) + " is for frame " + std::to_string(frameId) + ", which was never set up",
          false, frameId, tileId);
    return;
  }
  TileWork work{it->second, {}, {}, frameId, tileId};
  try {
    work.rect = proto::decodeTileRect(request, it->second->renderer->frame());
  } catch (const InputError& e) {
    error(wire::ErrorCode::BadTile, e.what(), false, frameId, tileId);
    return;
  }
  if (request.mask()) work.mask.assign(request.mask()->begin(), request.mask()->end());
  host_.trace(std::move(work));
}

void Session::onCancel(const wire::Cancel& cancel) {
  std::vector<std::uint32_t> tiles;
  if (cancel.tile_ids()) tiles.assign(cancel.tile_ids()->begin(), cancel.tile_ids()->end());
  host_.cancel(cancel.frame_id(), tiles);
}

}  // namespace glint::server
