#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/base/build_identity.h"
#include "common/render/irradiance_field.h"
#include "common/render/ray_stats.h"
#include "common/scene/scene.h"
#include "common/render/tile.h"
#include "proto/framing.h"
#include "proto/scene_bundle.h"

namespace glint::proto {

// Encoders: each returns one framed message, ready to write.
// Hello carries this build's identity (common/base/build_identity.h); a test may
// pose as another build.
std::vector<std::uint8_t> encodeHello(std::uint32_t maxMessageBytes, std::uint32_t threads,
                                      const std::string& software, const std::string& build = buildIdentity());
std::vector<std::uint8_t> encodeSceneQuery(const SceneHash& hash, std::span<const SceneHash> files = {});
std::vector<std::uint8_t> encodeSceneStatus(const SceneHash& hash, bool present,
                                            std::span<const std::uint32_t> missing = {});
// The scene's text and each file's path and hash (`fileHashes`, in the
// bundle's order, as BundleDigest::files); the bytes go in FileChunks.
std::vector<std::uint8_t> encodeSceneUpload(const SceneHash& hash, const SceneBundle& bundle,
                                            std::span<const SceneHash> fileHashes);
// The same, hashing the files here.
std::vector<std::uint8_t> encodeSceneUpload(const SceneHash& hash, const SceneBundle& bundle);
std::vector<std::uint8_t> encodeFileChunk(const SceneHash& file, std::uint64_t size, std::uint64_t offset,
                                          std::string_view data);
// A file (whose SHA-256 is `hash`) as FileChunks of at most chunkBytes each
// (one, empty, for an empty file).
std::vector<std::vector<std::uint8_t>> encodeFileChunks(std::string_view bytes, const SceneHash& hash,
                                                        std::size_t chunkBytes);
std::vector<std::uint8_t> encodeSceneReady(const SceneHash& hash, float buildMs);
// What a frame's tiles are: pixels (path transport's light between
// surfaces read from `field`, when it has one, which the connection was sent
// whole) or, with `fill`, batches of `field`'s probes to fill.
struct FrameWork {
  std::optional<FieldSettings> field;
  bool fill = false;
};
std::vector<std::uint8_t> encodeFrameSetup(std::uint32_t frameId, const SceneHash& hash, const FrameSettings& frame,
                                           const FrameWork& work = {});
std::vector<std::uint8_t> encodeTileRequest(std::uint32_t frameId, std::uint32_t tileId, const TileRect& rect,
                                            std::span<const std::uint8_t> mask);
// `probes`: a fill frame's (FrameWork::fill) values, rgb then empty.
std::vector<std::uint8_t> encodeTileResult(std::uint32_t frameId, std::uint32_t tileId,
                                           std::span<const std::uint8_t> rgb, const RayStats& rays,
                                           std::uint32_t computeMicros, std::span<const float> probes = {});
// An irradiance field of the scene `hash` as FieldPieces of at most
// maxBytes of values each (at least one probe a piece).
std::vector<std::vector<std::uint8_t>> encodeFieldPieces(const SceneHash& hash, const IrradianceField& field,
                                                         std::size_t maxBytes);
std::vector<std::uint8_t> encodeError(wire::ErrorCode code, const std::string& message, std::uint32_t frameId = 0,
                                      std::uint32_t tileId = 0);
// tileIds empty: every tile of the frame.
std::vector<std::uint8_t> encodeCancel(std::uint32_t frameId, std::span<const std::uint32_t> tileIds);
std::vector<std::uint8_t> encodeGoodbye();

// Decoders of verified messages that check every value and throw InputError
// naming the field ("frame_setup.eye: not finite").
SceneHash decodeHash(const flatbuffers::Vector<std::uint8_t>* bytes, const char* field);
FrameSettings decodeFrameSettings(const wire::FrameSetup& setup, std::size_t maxPixels);
FrameWork decodeFrameWork(const wire::FrameSetup& setup);
// A FieldSpec's settings, checked as the scene's tracing.field is.
FieldSettings decodeFieldSpec(const wire::FieldSpec* spec, const char* field);
SceneHash decodeHash32(const wire::Hash32* hash, const char* field);
// SceneQuery.files (at most maxFiles of them).
std::vector<SceneHash> decodeFileHashes(const wire::SceneQuery& query, std::size_t maxFiles);
// A SceneUpload: the text and each file's path and hash.
struct SceneManifest {
  std::string text;
  std::vector<std::pair<std::string, SceneHash>> files;
};
SceneManifest decodeManifest(const wire::SceneUpload& upload);
// The tile's rectangle, checked against the frame's size, and its mask,
// checked against the rectangle.
TileRect decodeTileRect(const wire::TileRequest& tile, const FrameSettings& frame);
// A fill frame's batch: probes [x, x + width) of a field of `probeCount`,
// at most kMaxBatchProbes (y 0, height 1, no mask).
constexpr int kMaxBatchProbes = 4096;
TileRect decodeProbeBatch(const wire::TileRequest& tile, int probeCount);
RayStats decodeRays(const wire::RayCounts* rays);

// A name for each message kind, for logs and errors; "type N" for a kind
// this build does not know.
std::string bodyName(wire::Body body);

}  // namespace glint::proto
