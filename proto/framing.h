#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <flatbuffers/flatbuffers.h>

#include "proto/glint_generated.h"

namespace glint::proto {

// 2: Hello.build, Cancel; 3: files by hash, FileChunk; 4: path counts in RayCounts; 5: the irradiance field
// (FrameSetup.field and fill_field, TileResult.probes, FieldPiece); 6: RayCounts.path_bounces
constexpr std::uint32_t kProtocolVersion = 6;
constexpr std::size_t kHeaderBytes = 4;  // little-endian uint32 length
constexpr std::size_t kDefaultMaxMessageBytes = std::size_t{64} << 20;
// The most file bytes one FileChunk carries (less where a server's message
// limit is smaller).
constexpr std::size_t kFileChunkBytes = std::size_t{4} << 20;
// The most files one scene may name (SceneQuery.files), and the most files
// one client may have arriving at once.
constexpr std::size_t kMaxSceneFiles = 65536;
// A server keeps the setup of a client's last 16 frames; tiles of older ones
// are refused, and a client stops expecting their results.
constexpr std::uint32_t kFramesRemembered = 16;

// A tile's key in a frame: where requests, results and cancels are matched,
// on either end.
inline std::uint64_t tileKey(std::uint32_t frameId, std::uint32_t tileId) {
  return std::uint64_t{frameId} << 32 | tileId;
}

// The length a frame header announces.
std::uint32_t frameLength(std::span<const std::uint8_t, kHeaderBytes> header);

// Finishes `builder` with the "GLNT" identifier and returns the framed bytes
// (length prefix + message), ready to write.
std::vector<std::uint8_t> finishFrame(flatbuffers::FlatBufferBuilder& builder,
                                      flatbuffers::Offset<wire::Message> message);

enum class DecodeStatus {
  kNeedMore,  // not a whole frame yet
  kBad,       // cannot be a valid frame: close the connection after an Error
  kGood,
};

struct Decoded {
  DecodeStatus status = DecodeStatus::kNeedMore;
  std::size_t consumed = 0;               // bytes of the frame, header included (kGood)
  const wire::Message* message = nullptr;  // points into the bytes given (kGood)
  std::string error;                       // what is wrong (kBad)
  wire::ErrorCode code = wire::ErrorCode::Malformed;
};

// Decodes the first frame of a byte stream: a pure function, no I/O. The
// length is checked against maxMessageBytes before anything else, and the
// message passes flatbuffers::Verifier with explicit limits. FlatBuffers reads
// fields in place, so the message must lie 8-aligned: where it does not (a
// frame in the middle of a stream), it is copied into `aligned` first.
// Decoded::message points into `bytes` or `aligned`; both must stay untouched
// while it is used.
Decoded decodeFrame(std::span<const std::uint8_t> bytes, std::size_t maxMessageBytes,
                    std::vector<std::uint64_t>& aligned);

// Verifies a message body (no length prefix) held 8-aligned in memory;
// nullptr and `error` if invalid (or not aligned: a receiver's bug).
const wire::Message* verifyMessage(std::span<const std::uint8_t> body, std::string* error);

}  // namespace glint::proto
