#include "client/farm/server_conversation.h"

#include <algorithm>
#include <cmath>

#include "common/base/build_identity.h"
#include "common/base/printable.h"
#include "proto/messages.h"

namespace glint {
namespace {

constexpr const char* kSceneWait = "scene upload and build; --scene-timeout";
constexpr std::uint32_t kMaxThreadsBelieved = 4096;  // sizes the dispatcher's window, nothing more

}  // namespace

ServerConversation::ServerConversation(ConversationHost& host, const proto::SceneBundle& bundle,
                                       const proto::BundleDigest& digest, const LinkTimeouts& timeouts)
    : host_(host), bundle_(bundle), digest_(digest), timeouts_(timeouts) {}

void ServerConversation::await(std::chrono::milliseconds timeout, const char* waitingFor) {
  waited_ = timeout;
  waitingFor_ = waitingFor;
  host_.await(timeout);
}

void ServerConversation::start() {
  await(timeouts_.connect, "connecting");
}

void ServerConversation::connected() {
  if (state_ != State::kConnecting) return;
  state_ = State::kHello;
  await(timeouts_.connect, "Hello");
  host_.send(proto::encodeHello(static_cast<std::uint32_t>(maxMessageBytes_), 0, "glint 0.1"));
}

void ServerConversation::timedOut() {
  fail(LinkFailure::Kind::kUnreachable,
       "no answer within " + std::to_string(waited_.count() / 1000) + " s (" + waitingFor_ + ")");
}

void ServerConversation::wrote(std::size_t bytes) {
  if (state_ == State::kUpload && bytes > 0) await(timeouts_.scene, kSceneWait);  // still moving
}

// Before the server's Hello, a close is a refusal: of our certificate (TLS),
// of a client that speaks plain TCP to a TLS server, or of our Hello.
void ServerConversation::streamEnded(const std::string& why) {
  if (state_ != State::kHello) return fail(LinkFailure::Kind::kClosed, why);
  if (why != "closed the connection") return fail(LinkFailure::Kind::kRefused, why);
  fail(LinkFailure::Kind::kRefused,
       "closed the connection before answering Hello (does it want TLS? then give --tls-ca, --tls-cert and "
       "--tls-key)");
}

void ServerConversation::fail(LinkFailure::Kind kind, const std::string& what) {
  if (over()) return;
  state_ = State::kFailed;
  host_.stopWaiting();
  host_.lost({kind, what});
}

void ServerConversation::close() {
  if (over()) return;
  host_.send(proto::encodeGoodbye());
  state_ = State::kClosed;
  host_.stopWaiting();
}

void ServerConversation::handle(const wire::Message& m) {
  if (over()) return;
  if (const auto* e = m.body_as_Error()) return onError(*e);
  if (state_ == State::kHello && m.body_type() == wire::Body::Hello) return onHello(*m.body_as_Hello());
  if (state_ == State::kQuery && m.body_type() == wire::Body::SceneStatus) {
    return onSceneStatus(*m.body_as_SceneStatus());
  }
  if (state_ == State::kUpload && m.body_type() == wire::Body::SceneReady) return becomeReady();
  if (state_ == State::kReady && m.body_type() == wire::Body::TileResult) return onResult(*m.body_as_TileResult());
  fail(LinkFailure::Kind::kBadBytes, std::string("sent an unexpected ") + proto::bodyName(m.body_type()) + " message");
}

void ServerConversation::onHello(const wire::Hello& hello) {
  const std::string build = hello.build() ? hello.build()->str() : "(none)";
  if (build != buildIdentity()) {
    fail(LinkFailure::Kind::kRefused, "its pixels would differ from this client's (server build '" + printable(build) +
                                          "', client build '" + buildIdentity() +
                                          "'); run glint and glintd from the same build");
    return;
  }
  maxMessageBytes_ = std::min<std::size_t>(maxMessageBytes_, hello.max_message_bytes());
  threads_ = static_cast<int>(std::clamp<std::uint32_t>(hello.threads(), 1, kMaxThreadsBelieved));
  state_ = State::kQuery;
  host_.send(proto::encodeSceneQuery(digest_.scene, digest_.files));
}

// The server lacks the scene: the files it lacks, in pieces within its
// message limit, then the scene's text and file list.
void ServerConversation::onSceneStatus(const wire::SceneStatus& status) {
  if (status.present()) return becomeReady();
  std::vector<std::uint8_t> upload = proto::encodeSceneUpload(digest_.scene, bundle_, digest_.files);
  if (upload.size() - proto::kHeaderBytes > maxMessageBytes_) {
    fail(LinkFailure::Kind::kRefused, "the scene file's text (" + std::to_string(bundle_.text.size()) +
                                          " bytes) is over the server's message limit of " +
                                          std::to_string(maxMessageBytes_) +
                                          " bytes; start glintd with a larger --max-message-mb");
    return;
  }
  if (!sendMissingFiles(status)) return;
  state_ = State::kUpload;
  uploaded_ = true;
  await(timeouts_.scene, kSceneWait);
  host_.send(std::move(upload));
}

bool ServerConversation::sendMissingFiles(const wire::SceneStatus& status) {
  std::vector<const std::string*> files;
  for (const auto& [path, bytes] : bundle_.files) files.push_back(&bytes);
  constexpr std::size_t kChunkOverhead = 4096;  // the FileChunk's own fields and framing
  const std::size_t chunkBytes =
      std::min(proto::kFileChunkBytes,
               maxMessageBytes_ > 2 * kChunkOverhead ? maxMessageBytes_ - kChunkOverhead : kChunkOverhead);
  if (!status.missing()) return true;
  std::vector<bool> sent(files.size(), false);  // a server asking twice gets a file once
  for (const std::uint32_t i : *status.missing()) {
    if (i >= files.size()) {
      fail(LinkFailure::Kind::kBadBytes,
           "asked for file " + std::to_string(i) + " of a scene of " + std::to_string(files.size()) + " files");
      return false;
    }
    if (sent[i]) continue;
    sent[i] = true;
    for (auto& chunk : proto::encodeFileChunks(*files[i], digest_.files[i], chunkBytes)) host_.send(std::move(chunk));
  }
  return true;
}

void ServerConversation::becomeReady() {
  state_ = State::kReady;
  host_.stopWaiting();
  host_.serving();
}

void ServerConversation::onError(const wire::Error& error) {
  const std::string text = std::string(wire::EnumNameErrorCode(error.code())) + ": " +
                           (error.message() ? printable(error.message()->string_view()) : "");
  switch (error.code()) {
    case wire::ErrorCode::BadScene:
      return fail(LinkFailure::Kind::kSceneError, text);
    case wire::ErrorCode::Busy:
      return fail(state_ == State::kReady ? LinkFailure::Kind::kServerError : LinkFailure::Kind::kBusy, text);
    case wire::ErrorCode::Version:
    case wire::ErrorCode::ShuttingDown:
      return fail(state_ == State::kReady ? LinkFailure::Kind::kServerError : LinkFailure::Kind::kRefused, text);
    default:
      return fail(LinkFailure::Kind::kServerError, text);
  }
}

void ServerConversation::setupFrame(std::uint32_t frameId, const FrameSettings& frame, const proto::FrameWork& work) {
  if (frameId > proto::kFramesRemembered) {  // results of frames the server forgot will not come
    std::erase_if(pending_, [&](const auto& p) { return p.first >> 32 <= frameId - proto::kFramesRemembered; });
  }
  fillFrame_ = work.fill ? std::optional(frameId) : std::nullopt;
  host_.send(proto::encodeFrameSetup(frameId, digest_.scene, frame, work));
}

void ServerConversation::request(std::uint32_t frameId, std::uint32_t tileId, const TileJob& job) {
  const bool batch = fillFrame_ == frameId;
  pending_[proto::tileKey(frameId, tileId)] =
      batch ? Expected{0, static_cast<std::size_t>(job.rect.width) * IrradianceField::kProbeFloats}
            : Expected{3 * tracedPixels(job), 0};
  host_.send(proto::encodeTileRequest(frameId, tileId, job.rect, job.mask));
}

void ServerConversation::sendField(const IrradianceField& field) {
  for (std::vector<std::uint8_t>& piece : proto::encodeFieldPieces(digest_.scene, field, maxMessageBytes_ / 2)) {
    host_.send(std::move(piece));
  }
}

void ServerConversation::cancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds) {
  if (state_ == State::kReady) host_.send(proto::encodeCancel(frameId, tileIds));
}

// A result must answer a request of this server (a cancelled one may still
// come) with one RGB triple per masked pixel.
void ServerConversation::onResult(const wire::TileResult& result) {
  const auto it = pending_.find(proto::tileKey(result.frame_id(), result.tile_id()));
  const std::string tile =
      "tile " + std::to_string(result.tile_id()) + " of frame " + std::to_string(result.frame_id());
  if (it == pending_.end()) {
    fail(LinkFailure::Kind::kBadBytes, "sent " + tile + ", which was not asked of it (or came twice)");
    return;
  }
  const std::size_t rgbBytes = result.rgb() ? result.rgb()->size() : 0;
  const std::size_t probeValues = result.probes() ? result.probes()->size() : 0;
  if (rgbBytes != it->second.rgb) {
    fail(LinkFailure::Kind::kBadBytes, "sent " + tile + " with " + std::to_string(rgbBytes) + " bytes of pixels, not " +
                                           std::to_string(it->second.rgb));
    return;
  }
  if (probeValues != it->second.probes) {
    fail(LinkFailure::Kind::kBadBytes, "sent " + tile + " with " + std::to_string(probeValues) +
                                           " probe values, not " + std::to_string(it->second.probes));
    return;
  }
  pending_.erase(it);
  TileOutput out;
  if (result.rgb()) out.rgb.assign(result.rgb()->begin(), result.rgb()->end());
  if (result.probes()) out.probes.assign(result.probes()->begin(), result.probes()->end());
  if (!std::all_of(out.probes.begin(), out.probes.end(), [](float v) { return std::isfinite(v); })) {
    fail(LinkFailure::Kind::kBadBytes, "sent " + tile + " with probe values that are not finite");
    return;
  }
  out.rays = proto::decodeRays(result.rays());
  out.computeMs = result.compute_us() / 1000.0;
  host_.delivered(result.frame_id(), result.tile_id(), std::move(out));
}

}  // namespace glint
