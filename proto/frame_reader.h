#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "proto/framing.h"

namespace glint::proto {

// The first size of a reader's buffer, and what an idle one keeps.
constexpr std::size_t kReadChunkBytes = 64 * 1024;

// Framed messages out of a byte stream, whatever carries it (glintd's
// connections and glint's links alike): the carrier reads into space(),
// says how many bytes came with filled(), then takes the whole messages
// held with next(). Memory follows the bytes that arrive, not the length a
// header announces: the buffer grows by at most what it holds
// (kReadChunkBytes to start), so a peer that announces 64 MiB and sends 4
// bytes costs 64 KiB; a length over the limit is refused as soon as its
// header is held, before its body is read. An idle reader gives a large
// buffer back.
class FrameReader {
 public:
  // Where the next read goes (never empty). Invalidates the last message.
  std::span<std::uint8_t> space();
  void filled(std::size_t n);
  // The next whole message held (kGood; valid until the next space()),
  // kNeedMore, or kBad with its error code and reason (the reader is then
  // of no further use).
  Decoded next(std::size_t maxMessageBytes);
  // Bytes of a message not yet whole are held.
  bool midMessage() const { return end_ > begin_; }

 private:
  std::vector<std::uint8_t> buffer_;
  std::size_t begin_ = 0;  // the first byte not yet taken
  std::size_t end_ = 0;    // the end of the bytes held
  std::vector<std::uint64_t> aligned_;
};

}  // namespace glint::proto
