#include "server/session.h"

#include <cmath>

#include "common/base/error.h"
#include "common/scene/frame_limits.h"
#include "common/base/timing.h"
#include "proto/messages.h"
#include "server/log.h"

namespace glint::server {
namespace {


std::string shortHash(const proto::SceneHash& hash) { return proto::toHex(hash).substr(0, 12); }

}  // namespace

std::vector<std::uint8_t> traceTile(const TileWork& work) {
  const auto start = Clock::now();
  std::vector<std::uint8_t> rgb;
  std::vector<float> probes;
  RayStats rays;
  if (work.frame->probes) {  // a batch of probes [x, x + width)
    constexpr int kFloats = IrradianceField::kProbeFloats;
    probes.resize(static_cast<std::size_t>(work.rect.width) * kFloats);
    for (int i = 0; i < work.rect.width; ++i) {
      IrradianceField::writeProbe(work.frame->probes->trace(work.rect.x + i, rays),
                                  std::span<float, kFloats>(probes.data() + static_cast<std::size_t>(i) * kFloats, kFloats));
    }
  } else {
    work.frame->renderer->renderTile(work.rect, work.mask, rgb, rays);
  }
  const auto micros = static_cast<std::uint32_t>(msSince(start) * 1000.0);
  return proto::encodeTileResult(work.frameId, work.tileId, rgb, rays, micros, probes);
}

Session::Session(SessionHost& host, const SessionStores& stores, const Settings& settings, std::string peer)
    : host_(host), stores_(stores), settings_(settings), peer_(std::move(peer)) {}

Session::~Session() {
  for (const auto& [hash, file] : partial_) stores_.uploads.give(file.taken);
  stores_.uploads.give(field_.taken);
}

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
  const wire::Body kind = m.body_type();
  if (kind == wire::Body::SceneUpload || kind == wire::Body::FileChunk || kind == wire::Body::FrameSetup ||
      kind == wire::Body::TileRequest || kind == wire::Body::FieldPiece) {
    host_.worked();
  }
  // verifyMessage guarantees that the body named is there.
  switch (m.body_type()) {
    case wire::Body::Hello:
      return onHello(*m.body_as_Hello());
    case wire::Body::SceneQuery:
      return onSceneQuery(*m.body_as_SceneQuery());
    case wire::Body::SceneUpload:
      return onSceneUpload(*m.body_as_SceneUpload());
    case wire::Body::FileChunk:
      return onFileChunk(*m.body_as_FileChunk());
    case wire::Body::FrameSetup:
      return onFrameSetup(*m.body_as_FrameSetup());
    case wire::Body::TileRequest:
      return onTileRequest(*m.body_as_TileRequest());
    case wire::Body::Cancel:
      return onCancel(*m.body_as_Cancel());
    case wire::Body::FieldPiece:
      return onFieldPiece(*m.body_as_FieldPiece());
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
          "the server has its maximum of " + std::to_string(settings_.maxClients) + " clients, none idle; try later",
          true);
    return;
  }
  state_ = State::kServing;
  host_.reply(proto::encodeHello(settings_.maxMessageBytes, settings_.threads, "glintd 0.1"));
}

// The scene, if held; otherwise which of its files are not held either.
void Session::onSceneQuery(const wire::SceneQuery& query) {
  const proto::SceneHash hash = proto::decodeHash(query.hash(), "scene_query.hash");
  if (stores_.scenes.find(hash)) {
    host_.reply(proto::encodeSceneStatus(hash, true));
    return;
  }
  const std::vector<proto::SceneHash> files = proto::decodeFileHashes(query, proto::kMaxSceneFiles);
  std::vector<std::uint32_t> missing;
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!stores_.files.find(files[i])) missing.push_back(static_cast<std::uint32_t>(i));
  }
  host_.reply(proto::encodeSceneStatus(hash, false, missing));
}

// The scene put together from files this server holds; its hash is checked
// when it is built.
void Session::onSceneUpload(const wire::SceneUpload& upload) {
  if (building_) {
    error(wire::ErrorCode::UnknownMessage,
          "scene_upload: this connection's last scene is still being built; one at a time (wait for its SceneReady "
          "or Error)",
          false);
    return;
  }
  const proto::SceneHash hash = proto::decodeHash(upload.hash(), "scene_upload.hash");
  proto::SceneManifest manifest = proto::decodeManifest(upload);
  auto bundle = std::make_shared<proto::SceneBundle>();
  bundle->text = std::move(manifest.text);
  for (const auto& [path, fileHash] : manifest.files) {
    const std::shared_ptr<const std::string> bytes = stores_.files.find(fileHash);
    if (!bytes) {
      error(wire::ErrorCode::BadScene,
            "scene_upload.files: '" + path + "' (" + shortHash(fileHash) +
                ") is not on this server; send its FileChunks before the SceneUpload",
            false);
      return;
    }
    bundle->files[path] = *bytes;
  }
  building_ = true;
  host_.build({hash, std::move(bundle)});
}

// A piece of a file: in order, within the size announced with the first
// piece, which must fit the upload memory; the whole is checked against its
// hash and kept for every client.
void Session::onFileChunk(const wire::FileChunk& chunk) {
  const proto::SceneHash hash = proto::decodeHash32(chunk.hash(), "file_chunk.hash");
  if (stores_.files.find(hash)) return;  // held already (another client sent it meanwhile)
  if (!partial_.count(hash) && partial_.size() >= proto::kMaxSceneFiles) {
    error(wire::ErrorCode::Malformed, "file_chunk: more than " + std::to_string(proto::kMaxSceneFiles) +
                                          " files arriving at once", false);
    return;
  }
  const auto [it, fresh] = partial_.try_emplace(hash);
  PartialFile& file = it->second;
  if (fresh) file.size = chunk.size();
  const std::size_t n = chunk.data() ? chunk.data()->size() : 0;
  const auto fail = [&](const std::string& why) {
    dropPartial(hash);
    error(wire::ErrorCode::Malformed, "file_chunk " + shortHash(hash) + ": " + why, false);
  };
  if (chunk.size() != file.size) return fail("the size changed from " + std::to_string(file.size));
  if (chunk.offset() != file.bytes.size()) {
    return fail("offset " + std::to_string(chunk.offset()) + ", expected " + std::to_string(file.bytes.size()) +
                " (pieces come in order)");
  }
  if (n > file.size - file.bytes.size()) return fail("more bytes than the size " + std::to_string(file.size));
  if (file.size > settings_.maxFileBytes || !stores_.uploads.take(n)) {
    return fail("a file of " + std::to_string(file.size) + " bytes does not fit what this server holds for uploads (" +
                stores_.uploads.name() + ")");
  }
  file.taken += n;
  if (n > 0) file.bytes.append(reinterpret_cast<const char*>(chunk.data()->data()), n);
  if (file.bytes.size() < file.size) return;
  if (proto::sha256(file.bytes) != hash) return fail("its bytes do not match its hash");
  std::string bytes = std::move(file.bytes);
  dropPartial(hash);
  logLine(peer_ + ": file " + shortHash(hash) + " received (" + std::to_string(bytes.size()) + " bytes)");
  stores_.files.insert(hash, std::move(bytes));
}

void Session::dropPartial(const proto::SceneHash& hash) {
  const auto it = partial_.find(hash);
  if (it == partial_.end()) return;
  stores_.uploads.give(it->second.taken);
  partial_.erase(it);
}

void Session::sceneBuilt(const BuiltScene& built) {
  building_ = false;
  if (state_ == State::kEnded) return;
  if (!built.prepared) {
    logLine(peer_ + ": scene " + shortHash(built.hash) + " rejected");
    error(wire::ErrorCode::BadScene, built.error, false);
    return;
  }
  stores_.scenes.insert(built.hash, built.prepared);
  logLine(peer_ + ": scene " + shortHash(built.hash) + " built in " + std::to_string(built.ms) + " ms (" +
          std::to_string(built.prepared->scene().geometry.primitiveCount()) + " primitives)");
  host_.reply(proto::encodeSceneReady(built.hash, static_cast<float>(built.ms)));
}

void Session::onFrameSetup(const wire::FrameSetup& setup) {
  const std::uint32_t frameId = setup.frame_id();
  try {
    const proto::SceneHash hash = proto::decodeHash(setup.scene_hash(), "frame_setup.scene_hash");
    auto scene = stores_.scenes.find(hash);
    if (!scene) {
      error(wire::ErrorCode::UnknownScene, "scene " + shortHash(hash) + " is not on this server; upload it first",
            false, frameId);
      return;
    }
    const FrameSettings settings = proto::decodeFrameSettings(setup, FrameLimits::kMaxPixels);
    const proto::FrameWork work = proto::decodeFrameWork(setup);
    auto frame = std::make_shared<SessionFrame>();
    frame->scene = std::move(scene);
    if (work.fill) {
      frame->grid = std::make_unique<FieldGrid>(frame->scene->scene().geometry.bounds(), *work.field);
      frame->probes = std::make_unique<ProbeTracer>(*frame->scene, settings, *frame->grid);
    } else {
      setUpPixels(*frame, settings, work, hash);
    }
    frames_[frameId] = std::move(frame);
    while (frames_.size() > proto::kFramesRemembered) frames_.erase(frames_.begin());
  } catch (const InputError& e) {
    error(wire::ErrorCode::BadFrame, e.what(), false, frameId);
  }
}

void Session::setUpPixels(SessionFrame& frame, const FrameSettings& settings, const proto::FrameWork& work,
                          const proto::SceneHash& hash) {
  if (work.field) {
    const bool held = field_.whole() && field_.scene == hash && field_.field->settings().probes == work.field->probes &&
                      field_.field->settings().rays == work.field->rays;
    if (!held) {
      throw InputError("frame_setup.field: this connection has not sent an irradiance field of " +
                       std::to_string(work.field->probes) + " probes and " + std::to_string(work.field->rays) +
                       " rays for this scene; send its FieldPieces first");
    }
    if (settings.tracing.transport != Transport::kPath) {
      throw InputError("frame_setup.field: an irradiance field carries path transport's light (transport 1)");
    }
    frame.field = field_.field;
  }
  frame.renderer = std::make_unique<Renderer>(*frame.scene, settings, EffectPlan::derive(frame.scene->scene(), settings),
                                              frame.field.get());
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
    const SessionFrame& frame = *it->second;
    work.rect = frame.grid ? proto::decodeProbeBatch(request, frame.grid->probeCount())
                           : proto::decodeTileRect(request, frame.renderer->frame());
  } catch (const InputError& e) {
    error(wire::ErrorCode::BadTile, e.what(), false, frameId, tileId);
    return;
  }
  if (request.mask()) work.mask.assign(request.mask()->begin(), request.mask()->end());
  host_.trace(std::move(work));
}

// The pieces of a field, in order from probe 0; the whole field's memory is
// drawn from the uploads when its first piece comes, and given back when
// another replaces it or the session ends.
void Session::onFieldPiece(const wire::FieldPiece& piece) {
  const auto fail = [&](const std::string& why) {
    dropField();
    error(wire::ErrorCode::Malformed, "field_piece: " + why, false);
  };
  try {
    const proto::SceneHash hash = proto::decodeHash(piece.scene_hash(), "field_piece.scene_hash");
    const FieldSettings settings = proto::decodeFieldSpec(piece.field(), "field_piece.field");
    if (piece.first() == 0) {
      dropField();
      const std::shared_ptr<const PreparedScene> scene = stores_.scenes.find(hash);
      if (!scene) return fail("scene " + shortHash(hash) + " is not on this server; upload it first");
      const FieldGrid grid(scene->scene().geometry.bounds(), settings);
      const std::size_t bytes = static_cast<std::size_t>(grid.probeCount()) * sizeof(IrradianceField::Probe);
      if (!stores_.uploads.take(bytes)) {
        return fail("a field of " + std::to_string(bytes) + " bytes does not fit what this server holds for uploads (" +
                    stores_.uploads.name() + ")");
      }
      field_.taken = bytes;
      field_.scene = hash;
      field_.field = std::make_shared<IrradianceField>(scene->scene().geometry.bounds(), settings);
    }
    if (!field_.field || field_.whole() || piece.first() != static_cast<std::uint32_t>(field_.received) ||
        field_.scene != hash || field_.field->settings().probes != settings.probes ||
        field_.field->settings().rays != settings.rays) {
      return fail("a piece from probe " + std::to_string(piece.first()) + " of a field not being sent (pieces come in "
                  "order from probe 0, each of the same scene and settings)");
    }
    constexpr std::size_t kFloats = IrradianceField::kProbeFloats;
    const std::size_t n = piece.values() ? piece.values()->size() : 0;
    const std::size_t probes = n / kFloats;
    if (n == 0 || n % kFloats != 0 || probes > static_cast<std::size_t>(field_.field->probeCount() - field_.received)) {
      return fail(std::to_string(n) + " values: not whole probes of " + std::to_string(kFloats) + " within the field");
    }
    for (std::size_t i = 0; i < probes; ++i) {
      const float* at = piece.values()->data() + i * kFloats;
      for (std::size_t k = 0; k < kFloats; ++k) {
        if (!std::isfinite(at[k])) return fail("a value that is not finite");
      }
      field_.field->probe(field_.received++) = IrradianceField::readProbe(std::span<const float, kFloats>(at, kFloats));
    }
  } catch (const InputError& e) {
    fail(e.what());
  }
}

void Session::dropField() {
  stores_.uploads.give(field_.taken);
  field_ = {};
}

void Session::onCancel(const wire::Cancel& cancel) {
  std::vector<std::uint32_t> tiles;
  if (cancel.tile_ids()) tiles.assign(cancel.tile_ids()->begin(), cancel.tile_ids()->end());
  host_.cancel(cancel.frame_id(), tiles);
}

}  // namespace glint::server
