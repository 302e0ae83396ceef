#include "proto/messages.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "common/base/build_identity.h"
#include "common/base/error.h"
#include "common/math/finite.h"
#include "common/scene/frame_limits.h"

namespace glint::proto {
namespace {

using flatbuffers::FlatBufferBuilder;

template <typename T>
std::vector<std::uint8_t> finish(FlatBufferBuilder& b, flatbuffers::Offset<T> body, wire::Body type) {
  return finishFrame(b, wire::CreateMessage(b, type, body.Union()));
}

wire::Vec3 toWire(const glm::vec3& v) { return {v.x, v.y, v.z}; }
wire::Hash32 toWire(const SceneHash& h) { return wire::Hash32(flatbuffers::span<const std::uint8_t, 32>(h)); }

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

std::vector<std::uint8_t> encodeSceneQuery(const SceneHash& hash, std::span<const SceneHash> files) {
  FlatBufferBuilder b(files.size() * sizeof(wire::Hash32) + 128);
  std::vector<wire::Hash32> hashes;
  for (const SceneHash& f : files) hashes.push_back(toWire(f));
  const auto fileVector = b.CreateVectorOfStructs(hashes);
  return finish(b, wire::CreateSceneQuery(b, b.CreateVector(hash.data(), hash.size()), fileVector),
                wire::Body::SceneQuery);
}

std::vector<std::uint8_t> encodeSceneStatus(const SceneHash& hash, bool present,
                                            std::span<const std::uint32_t> missing) {
  FlatBufferBuilder b;
  const auto missingVector = b.CreateVector(missing.data(), missing.size());
  return finish(b, wire::CreateSceneStatus(b, b.CreateVector(hash.data(), hash.size()), present, missingVector),
                wire::Body::SceneStatus);
}

std::vector<std::uint8_t> encodeSceneUpload(const SceneHash& hash, const SceneBundle& bundle,
                                            std::span<const SceneHash> fileHashes) {
  FlatBufferBuilder b(bundle.text.size() + 1024);
  std::vector<flatbuffers::Offset<wire::SceneFile>> files;
  std::size_t i = 0;
  for (const auto& [path, bytes] : bundle.files) {
    const wire::Hash32 fileHash = toWire(fileHashes[i++]);
    files.push_back(wire::CreateSceneFile(b, b.CreateString(path), &fileHash));
  }
  const auto upload = wire::CreateSceneUpload(b, b.CreateVector(hash.data(), hash.size()),
                                              b.CreateString(bundle.text), b.CreateVector(files));
  return finish(b, upload, wire::Body::SceneUpload);
}

std::vector<std::uint8_t> encodeFileChunk(const SceneHash& file, std::uint64_t size, std::uint64_t offset,
                                          std::string_view data) {
  FlatBufferBuilder b(data.size() + 128);
  const auto bytes = b.CreateVector(reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
  const wire::Hash32 hash = toWire(file);
  return finish(b, wire::CreateFileChunk(b, &hash, size, offset, bytes), wire::Body::FileChunk);
}

std::vector<std::uint8_t> encodeSceneUpload(const SceneHash& hash, const SceneBundle& bundle) {
  return encodeSceneUpload(hash, bundle, digest(bundle).files);
}

std::vector<std::vector<std::uint8_t>> encodeFileChunks(std::string_view bytes, const SceneHash& hash,
                                                        std::size_t chunkBytes) {
  std::vector<std::vector<std::uint8_t>> chunks;
  std::size_t offset = 0;
  do {
    const std::size_t n = std::min(chunkBytes, bytes.size() - offset);
    chunks.push_back(encodeFileChunk(hash, bytes.size(), offset, bytes.substr(offset, n)));
    offset += n;
  } while (offset < bytes.size());
  return chunks;
}

std::vector<std::uint8_t> encodeSceneReady(const SceneHash& hash, float buildMs) {
  FlatBufferBuilder b;
  return finish(b, wire::CreateSceneReady(b, b.CreateVector(hash.data(), hash.size()), buildMs),
                wire::Body::SceneReady);
}

std::vector<std::uint8_t> encodeFrameSetup(std::uint32_t frameId, const SceneHash& hash, const FrameSettings& f,
                                           const FrameWork& work) {
  FlatBufferBuilder b;
  const auto hashVector = b.CreateVector(hash.data(), hash.size());
  const auto field = work.field ? wire::CreateFieldSpec(b, static_cast<std::uint32_t>(work.field->probes),
                                                        static_cast<std::uint32_t>(work.field->rays))
                                : flatbuffers::Offset<wire::FieldSpec>();
  const wire::Vec3 eye = toWire(f.camera.eye), lookAt = toWire(f.camera.lookAt), up = toWire(f.camera.up);
  const auto setup = wire::CreateFrameSetup(
      b, frameId, hashVector, static_cast<std::uint32_t>(f.width), static_cast<std::uint32_t>(f.height), &eye,
      &lookAt, &up, f.camera.fovY, f.sampling.pattern != SamplePattern::kRegular,
      static_cast<std::uint32_t>(f.sampling.samples), static_cast<std::uint8_t>(f.sampling.filter), f.sampling.seed,
      static_cast<std::uint32_t>(f.tracing.maxDepth), f.tracing.minWeight,
      f.sampling.pattern == SamplePattern::kAdaptive, f.sampling.adaptiveThreshold,
      f.output.encoding == Encoding::kSrgb, f.output.exposure, f.sampling.pattern == SamplePattern::kPerceptual,
      f.sampling.perceptualThreshold, static_cast<std::uint32_t>(f.sampling.lightSamples), f.camera.aperture,
      f.camera.focusDistance, static_cast<std::uint8_t>(f.tracing.transport),
      static_cast<std::uint32_t>(f.tracing.maxBounces), f.sampling.pattern == SamplePattern::kSobol, field, work.fill);
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
                                           std::uint32_t computeMicros, std::span<const float> probes) {
  FlatBufferBuilder b(rgb.size() + probes.size_bytes() + 128);
  const auto rgbVector = b.CreateVector(rgb.data(), rgb.size());
  const auto probeVector = probes.empty() ? flatbuffers::Offset<flatbuffers::Vector<float>>()
                                          : b.CreateVector(probes.data(), probes.size());
  const wire::RayCounts rays(r.primary, r.shadow, r.shadowBlocked, r.reflection, r.refraction, r.nonFiniteSamples,
                              r.paths, r.longestPath, r.lightSamples, r.pathBounces);
  return finish(b, wire::CreateTileResult(b, frameId, tileId, rgbVector, &rays, computeMicros, probeVector),
                wire::Body::TileResult);
}

std::vector<std::vector<std::uint8_t>> encodeFieldPieces(const SceneHash& hash, const IrradianceField& field,
                                                         std::size_t maxBytes) {
  constexpr int kFloats = IrradianceField::kProbeFloats;
  const int perPiece = std::max<int>(1, static_cast<int>(maxBytes / (kFloats * sizeof(float))));
  std::vector<std::vector<std::uint8_t>> pieces;
  std::vector<float> values;
  for (int first = 0; first < field.probeCount(); first += perPiece) {
    const int end = std::min(field.probeCount(), first + perPiece);
    values.assign(static_cast<std::size_t>(end - first) * kFloats, 0.0f);
    for (int i = first; i < end; ++i) {
      IrradianceField::writeProbe(field.probe(i),
                                  std::span<float, kFloats>(values.data() + static_cast<std::size_t>(i - first) * kFloats, kFloats));
    }
    FlatBufferBuilder b(values.size() * sizeof(float) + 128);
    const auto hashVector = b.CreateVector(hash.data(), hash.size());
    const auto spec = wire::CreateFieldSpec(b, static_cast<std::uint32_t>(field.settings().probes),
                                            static_cast<std::uint32_t>(field.settings().rays));
    const auto valueVector = b.CreateVector(values.data(), values.size());
    pieces.push_back(finish(b, wire::CreateFieldPiece(b, hashVector, spec, static_cast<std::uint32_t>(first), valueVector),
                            wire::Body::FieldPiece));
  }
  return pieces;
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
  s.paths = r->paths();
  s.longestPath = r->longest_path();
  s.lightSamples = r->light_samples();
  s.pathBounces = r->path_bounces();
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
  f.camera.aperture = s.aperture();
  f.camera.focusDistance = s.focus_distance();
  f.sampling.pattern = s.perceptual() ? SamplePattern::kPerceptual
                       : s.adaptive() ? SamplePattern::kAdaptive
                       : s.sobol()    ? SamplePattern::kSobol
                       : s.jittered() ? SamplePattern::kJittered
                                      : SamplePattern::kRegular;
  f.sampling.adaptiveThreshold = s.adaptive() ? s.adaptive_threshold() : f.sampling.adaptiveThreshold;
  f.sampling.perceptualThreshold = s.perceptual() ? s.perceptual_threshold() : f.sampling.perceptualThreshold;
  f.sampling.samples = toInt(s.samples());
  f.sampling.lightSamples = toInt(s.light_samples());
  if (s.filter() > static_cast<std::uint8_t>(FilterType::kMitchell)) throw InputError("frame_setup.filter: unknown");
  f.sampling.filter = static_cast<FilterType>(s.filter());
  f.sampling.seed = s.seed();
  f.tracing.maxDepth = toInt(s.max_depth());
  f.tracing.minWeight = s.min_weight();
  if (s.transport() > static_cast<std::uint8_t>(Transport::kPath)) throw InputError("frame_setup.transport: unknown");
  f.tracing.transport = static_cast<Transport>(s.transport());
  f.tracing.maxBounces = toInt(s.max_bounces());
  f.output.encoding = s.srgb() ? Encoding::kSrgb : Encoding::kLinear;
  f.output.exposure = s.exposure();
  checkFrame(f, maxPixels,
             {.size = "frame_setup.width, height",
              .camera = "frame_setup.",
              .samples = "frame_setup.samples",
              .seed = "frame_setup.seed",
              .maxDepth = "frame_setup.max_depth",
              .maxBounces = "frame_setup.max_bounces",
              .minWeight = "frame_setup.min_weight",
              .adaptiveThreshold = "frame_setup.adaptive_threshold",
              .perceptualThreshold = "frame_setup.perceptual_threshold",
              .lightSamples = "frame_setup.light_samples",
              .exposure = "frame_setup.exposure"});
  return f;
}

FieldSettings decodeFieldSpec(const wire::FieldSpec* spec, const char* field) {
  if (!spec) throw InputError(std::string(field) + ": missing");
  FieldSettings f;
  if (spec->probes() < static_cast<std::uint32_t>(FieldSettings::kMinProbes) ||
      spec->probes() > static_cast<std::uint32_t>(FieldSettings::kMaxProbes)) {
    throw InputError(std::string(field) + ".probes: must be from " + std::to_string(FieldSettings::kMinProbes) +
                     " to " + std::to_string(FieldSettings::kMaxProbes));
  }
  f.probes = static_cast<int>(spec->probes());
  f.rays = static_cast<int>(std::min<std::uint32_t>(spec->rays(), INT_MAX));
  if (const std::optional<std::string> why = FieldSettings::raysProblem(f.rays)) {
    throw InputError(std::string(field) + ".rays: " + *why);
  }
  return f;
}

FrameWork decodeFrameWork(const wire::FrameSetup& setup) {
  FrameWork work;
  if (setup.field()) work.field = decodeFieldSpec(setup.field(), "frame_setup.field");
  work.fill = setup.fill_field();
  if (work.fill && !work.field) throw InputError("frame_setup.fill_field: names no field (frame_setup.field)");
  return work;
}

SceneHash decodeHash32(const wire::Hash32* hash, const char* field) {
  if (!hash) throw InputError(std::string(field) + ": missing");
  SceneHash out{};
  std::copy(hash->bytes()->begin(), hash->bytes()->end(), out.begin());
  return out;
}

std::vector<SceneHash> decodeFileHashes(const wire::SceneQuery& query, std::size_t maxFiles) {
  std::vector<SceneHash> files;
  if (!query.files()) return files;
  if (query.files()->size() > maxFiles) {
    throw InputError("scene_query.files: " + std::to_string(query.files()->size()) + " files, over the limit of " +
                     std::to_string(maxFiles));
  }
  for (const wire::Hash32* f : *query.files()) files.push_back(decodeHash32(f, "scene_query.files"));
  return files;
}

SceneManifest decodeManifest(const wire::SceneUpload& upload) {
  SceneManifest manifest;
  if (!upload.text()) throw InputError("scene_upload.text: missing");
  manifest.text = upload.text()->str();
  if (upload.files()) {
    for (const wire::SceneFile* file : *upload.files()) {
      if (!file->path()) throw InputError("scene_upload.files: a file without a path");
      manifest.files.emplace_back(file->path()->str(), decodeHash32(file->hash(), "scene_upload.files.hash"));
    }
  }
  return manifest;
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

TileRect decodeProbeBatch(const wire::TileRequest& t, int probeCount) {
  const std::uint64_t first = t.x(), count = t.width();
  const bool masked = t.mask() && t.mask()->size() > 0;
  if (count == 0 || count > static_cast<std::uint64_t>(kMaxBatchProbes) ||
      first + count > static_cast<std::uint64_t>(probeCount) || t.y() != 0 || t.height() != 1 || masked) {
    throw InputError("tile " + std::to_string(t.tile_id()) + ": a batch of the field's " + std::to_string(probeCount) +
                     " probes must be probes [x, x + width) with width 1 to " + std::to_string(kMaxBatchProbes) +
                     ", y 0, height 1 and no mask (got " + std::to_string(count) + " from " + std::to_string(first) +
                     ")");
  }
  return {static_cast<int>(first), 0, static_cast<int>(count), 1};
}

std::string bodyName(wire::Body body) {
  const char* name = wire::EnumNameBody(body);
  return *name ? name : "type " + std::to_string(static_cast<int>(body));
}

}  // namespace glint::proto
