#include "proto/framing.h"

#include <cstring>

namespace glint::proto {
namespace {

// Verifier limits: the schema nests three tables deep (Message, body,
// SceneFile); a scene upload holds a few thousand tables at most.
constexpr flatbuffers::uoffset_t kMaxDepth = 16;
constexpr flatbuffers::uoffset_t kMaxTables = 100'000;

}  // namespace

std::uint32_t frameLength(std::span<const std::uint8_t, kHeaderBytes> header) {
  return static_cast<std::uint32_t>(header[0]) | static_cast<std::uint32_t>(header[1]) << 8 |
         static_cast<std::uint32_t>(header[2]) << 16 | static_cast<std::uint32_t>(header[3]) << 24;
}

std::vector<std::uint8_t> finishFrame(flatbuffers::FlatBufferBuilder& builder,
                                      flatbuffers::Offset<wire::Message> message) {
  wire::FinishMessageBuffer(builder, message);
  const auto size = static_cast<std::uint32_t>(builder.GetSize());
  std::vector<std::uint8_t> out(kHeaderBytes + size);
  out[0] = static_cast<std::uint8_t>(size);
  out[1] = static_cast<std::uint8_t>(size >> 8);
  out[2] = static_cast<std::uint8_t>(size >> 16);
  out[3] = static_cast<std::uint8_t>(size >> 24);
  std::copy(builder.GetBufferPointer(), builder.GetBufferPointer() + size, out.begin() + kHeaderBytes);
  return out;
}

const wire::Message* verifyMessage(std::span<const std::uint8_t> body, std::string* error) {
  if (reinterpret_cast<std::uintptr_t>(body.data()) % alignof(std::uint64_t) != 0) {
    *error = "internal error: a message was verified where it is not 8-aligned";
    return nullptr;
  }
  if (body.size() < 8 || !flatbuffers::BufferHasIdentifier(body.data(), wire::MessageIdentifier())) {
    *error = "not a Glint message (no GLNT identifier)";
    return nullptr;
  }
  flatbuffers::Verifier verifier(body.data(), body.size(), kMaxDepth, kMaxTables);
  if (!wire::VerifyMessageBuffer(verifier)) {
    *error = "message failed verification (truncated or corrupted)";
    return nullptr;
  }
  const wire::Message* message = wire::GetMessage(body.data());
  if (message->body_type() == wire::Body::NONE) {
    *error = "message has no body";
    return nullptr;
  }
  // The verifier accepts a union whose type is set and whose table is absent
  // (a missing table is valid FlatBuffers); no receiver can use such a message.
  if (!message->body()) {
    *error = std::string("message names a ") + wire::EnumNameBody(message->body_type()) + " body but carries none";
    return nullptr;
  }
  return message;
}

Decoded decodeFrame(std::span<const std::uint8_t> bytes, std::size_t maxMessageBytes,
                    std::vector<std::uint64_t>& aligned) {
  Decoded d;
  if (bytes.size() < kHeaderBytes) return d;
  const std::uint32_t length = frameLength(bytes.first<kHeaderBytes>());
  if (length > maxMessageBytes) {
    d.status = DecodeStatus::kBad;
    d.code = wire::ErrorCode::TooLarge;
    d.error = "message of " + std::to_string(length) + " bytes is over the limit of " +
              std::to_string(maxMessageBytes);
    return d;
  }
  if (bytes.size() < kHeaderBytes + length) return d;
  std::span<const std::uint8_t> body = bytes.subspan(kHeaderBytes, length);
  if (reinterpret_cast<std::uintptr_t>(body.data()) % alignof(std::uint64_t) != 0) {
    aligned.resize(length / sizeof(std::uint64_t) + 1);
    std::memcpy(aligned.data(), body.data(), length);
    body = {reinterpret_cast<const std::uint8_t*>(aligned.data()), length};
  }
  d.message = verifyMessage(body, &d.error);
  d.status = d.message ? DecodeStatus::kGood : DecodeStatus::kBad;
  d.consumed = kHeaderBytes + length;
  return d;
}

}  // namespace glint::proto
