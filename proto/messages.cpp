#include "proto/messages.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "common/build_identity.h"
#include "common/error.h"
#include "common/finite.h"
#include "common/frame_limits.h"

namespace glint::proto {
namespace {

using flatbuffers::FlatBufferBuilder;

template <typename T>
std::vector<std::uint8_t> finish(FlatBufferBuilder& b, flatbuffers::Offset<T> body, wire::Body type) {
  return finishFrame(b, wire::CreateMessage(b, type, body.Union()));
}

wire::Vec3 toWire(const glm::vec3& v) { return {v.x, v.y, v.z}; }

glm::vec3 fromWire(const wire::Vec3* v, const char* field) {
  if (!v) throw InputError(std::string("frame_setup.") + field + ": missing");
  const glm::vec3 out(v->x(), v->y(), v->z());
  if (!allFinite(out)) {
    throw InputError(std::string("frame_setup.") + field + ": not finite");
  }
  return out;
}

}  // namespace

std::vector<std::uint8_t> encodeHello(std::uint32_t maxMessageBytes, std::uint32_t threads,
                                      const std::string& software, const std::string& build) {
  FlatBufferBuilder b;
  const auto hello =
      wire::CreateHelloDirect(b, kProtocolVersion, maxMessageBytes, threads, software.c_str(), build.c_str());
  return finish(b, hello, wire::Body::Hello);
}

std::vector<std::uint8_t> encodeSceneQuery(const SceneHash& hash) {
  FlatBufferBuilder b;
  return finish(b, wire::CreateSceneQuery(b, b.CreateVector(hash.data(), hash.size())), wire::Body::SceneQuery);
}

std::vector<std::uint8_t> encodeSceneStatus(const SceneHash& hash, bool present) {
  FlatBufferBuilder b;
  return finish(b, wire::CreateSceneStatus(b, b.CreateVector(hash.data(), hash.size()), present),
                wire::Body::SceneStatus);
}

std::vector<std::uint8_t> encodeSceneUpload(const SceneHash& hash, const SceneBundle& bundle) {
  FlatBufferBuilder b(bundle.text.size() + 1024);
  std::vector<flatbuffers::Offset<wire::SceneFile>> files;
  for (const auto& [path, bytes] : bundle.files) {
    const auto data = b.CreateVector(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    files.push_back(wire::CreateSceneFile(b, b.CreateString(path), data));
  }
  const auto upload = wire::CreateSceneUpload(b, b.CreateVector(hash.data(), hash.size()),
                                              b.CreateString(bundle.text), b.CreateVector(files));
  return finish(b, upload, wire::Body::SceneUpload);
}

std::vector<std::uint8_t> encodeSceneReady(const SceneHash& hash, float buildMs) {
  FlatBufferBuilder b;
  return finish(b, wire::CreateSceneReady(b, b.CreateVector(hash.data(), hash.size()), buildMs),
                wire::Body::SceneReady);
}

std::vector<std::uint8_t> encodeFrameSetup(std::uint32_t frameId, const SceneHash& hash, const FrameSettings& f) {
  FlatBufferBuilder b;
  const auto hashVector = b.CreateVector(hash.data(), hash.size());
  const wire::Vec3 eye = toWire(f.camera.eye), lookAt = toWire(f.camera.lookAt), up = toWire(f.camera.up);
  const auto setup = wire::CreateFrameSetup(
      b, frameId, hashVector, static_cast<std::uint32_t>(f.width), static_cast<std::uint32_t>(f.height), &eye,
      &lookAt, &up, f.camera.fovY, f.sampling.pattern != SamplePattern::kRegular,
      static_cast<std::uint32_t>(f.sampling.samples), static_cast<std::uint8_t>(f.sampling.filter), f.sampling.seed,
      static_cast<std::uint32_t>(f.tracing.maxDepth), f.tracing.minWeight,
      f.sampling.pattern == SamplePattern::kAdaptive, f.sampling.adaptiveThreshold,
      f.output.encoding == Encoding::kSrgb, f.output.exposure);
  return finish(b, setup, wire::Body::FrameSetup);
}

std::vector<std::uint8_t> encodeTileRequest(std::uint32_t frameId, std::uint32_t tileId, const TileRect& r,
                                            std::span<const std::uint8_t> mask) {
  FlatBufferBuilder b(mask.size() + 128);
  const auto maskVector = b.CreateVector(mask.data(), mask.size());
  const auto tile = wire::CreateTileRequest(b, frameId, tileId, static_cast<std::uint32_t>(r.x),
                                            static_cast<std::uint32_t>(r.y), static_cast<std::uint32_t>(r.width),
                                            static_cast<std::uint32_t>(r.height), maskVector);
  return finish(b, tile, wire::Body::TileRequest);
}

std::vector<std::uint8_t> encodeTileResult(std::uint32_t frameId, std::uint32_t tileId,
                                           std::span<const std::uint8_t> rgb, const RayStats& r,
                                           std::uint32_t computeMicros) {
  FlatBufferBuilder b(rgb.size() + 128);
  const auto rgbVector = b.CreateVector(rgb.data(), rgb.size());
  const wire::RayCounts rays(r.primary, r.shadow, r.shadowBlocked, r.reflection, r.refraction, r.nonFiniteSamples);
  return finish(b, wire::CreateTileResult(b, frameId, tileId, rgbVector, &rays, computeMicros),
                wire::Body::TileResult);
}

RayStats decodeRays(const wire::RayCounts* r) {
  RayStats s;
  if (!r) return s;
  s.primary = r->primary();
  s.shadow = r->shadow();
  s.shadowBlocked = r->shadow_blocked();
  s.reflection = r->reflection();
  s.refraction = r->refraction();
  s.nonFiniteSamples = r->nonfinite_samples();
  return s;
}

std::vector<std::uint8_t> encodeError(wire::ErrorCode code, const std::string& message, std::uint32_t frameId,
                                      std::uint32_t tileId) {
  FlatBufferBuilder b;
  return finish(b, wire::CreateErrorDirect(b, code, message.c_str(), frameId, tileId), wire::Body::Error);
}

std::vector<std::uint8_t> encodeCancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds) {
  FlatBufferBuilder b;
  const auto tiles = b.CreateVector(tileIds.data(), tileIds.size());
  return finish(b, wire::CreateCancel(b, frameId, tiles), wire::Body::Cancel);
}

std::vector<std::uint8_t> encodeGoodbye() {
  FlatBufferBuilder b;
  return finish(b, wire::CreateGoodbye(b), wire::Body::Goodbye);
}

SceneHash decodeHash(const flatbuffers::Vector<std::uint8_t>* bytes, const char* field) {
  SceneHash hash{};
  if (!bytes || bytes->size() != hash.size()) throw InputError(std::string(field) + ": must be 32 bytes (SHA-256)");
  std::copy(bytes->begin(), bytes->end(), hash.begin());
  return hash;
}

FrameSettings decodeFrameSettings(const wire::FrameSetup& s, std::size_t maxPixels) {
  // Values beyond an int become INT_MAX, which the frame check refuses.
  const auto toInt = [](std::uint32_t v) { return static_cast<int>(std::min<std::uint32_t>(v, INT_MAX)); };
  FrameSettings f;
  f.width = toInt(s.width());
  f.height = toInt(s.height());
  f.camera.eye = fromWire(s.eye(), "eye");
  f.camera.lookAt = fromWire(s.look_at(), "look_at");
  f.camera.up = fromWire(s.up(), "up");
  f.camera.fovY = s.fov_y();
  f.sampling.pattern = s.adaptive()   ? SamplePattern::kAdaptive
                       : s.jittered() ? SamplePattern::kJittered
                                      : SamplePattern::kRegular;
  f.sampling.adaptiveThreshold = s.adaptive() ? s.adaptive_threshold() : f.sampling.adaptiveThreshold;
  f.sampling.samples = toInt(s.samples());
  if (s.filter() > static_cast<std::uint8_t>(FilterType::kMitchell)) throw InputError("frame_setup.filter: unknown");
  f.sampling.filter = static_cast<FilterType>(s.filter());
  f.sampling.seed = s.seed();
  f.tracing.maxDepth = toInt(s.max_depth());
  f.tracing.minWeight = s.min_weight();
  f.output.encoding = s.srgb() ? Encoding::kSrgb : Encoding::kLinear;
  f.output.exposure = s.exposure();
  checkFrame(f, maxPixels,
             {.size = "frame_setup.width, height",
              .camera = "frame_setup.",
              .samples = "frame_setup.samples",
              .seed = "frame_setup.seed",
              .maxDepth = "frame_setup.max_depth",
              .minWeight = "frame_setup.min_weight",
              .adaptiveThreshold = "frame_setup.adaptive_threshold",
              .exposure = "frame_setup.exposure"});
  return f;
}

SceneBundle decodeBundle(const wire::SceneUpload& upload) {
  SceneBundle bundle;
  if (!upload.text()) throw InputError("scene_upload.text: missing");
  bundle.text = upload.text()->str();
  if (upload.files()) {
    for (const wire::SceneFile* file : *upload.files()) {
      if (!file->path() || !file->data()) throw InputError("scene_upload.files: a file without path or data");
      bundle.files[file->path()->str()] = std::string(file->data()->begin(), file->data()->end());
    }
  }
  return bundle;
}

TileRect decodeTileRect(const wire::TileRequest& t, const FrameSettings& frame) {
  const std::uint64_t x = t.x(), y = t.y(), w = t.width(), h = t.height();
  if (w == 0 || h == 0 || x + w > static_cast<std::uint64_t>(frame.width) ||
      y + h > static_cast<std::uint64_t>(frame.height)) {
    throw InputError("tile " + std::to_string(t.tile_id()) + ": rectangle " + std::to_string(w) + "x" +
                     std::to_string(h) + " at (" + std::to_string(x) + ", " + std::to_string(y) +
                     ") is outside the " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                     " image");
  }
  const TileRect rect{static_cast<int>(x), static_cast<int>(y), static_cast<int>(w), static_cast<int>(h)};
  const std::size_t maskSize = t.mask() ? t.mask()->size() : 0;
  if (maskSize != 0 && maskSize != maskByteCount(rect)) {
    throw InputError("tile " + std::to_string(t.tile_id()) + ": mask of " + std::to_string(maskSize) +
                     " bytes, but the rectangle needs " + std::to_string(maskByteCount(rect)));
  }
  return rect;
}

const char* bodyName(wire::Body body) { return wire::EnumNameBody(body); }

}  // namespace glint::proto
