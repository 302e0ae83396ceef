#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "proto/frame_reader.h"

namespace glint::fuzz {

// Splits fuzz input into frames as both ends of the wire do, through a
// FrameReader fed in reads of an odd size (so that messages straddle reads
// and lie unaligned), and gives each verified message to `take` while
// `more()` holds. Stops at the first bad frame or the end of the input.
template <typename Take, typename More>
void forEachMessage(const std::uint8_t* data, std::size_t size, Take take, More more) {
  constexpr std::size_t kReadBytes = 4093;
  std::span<const std::uint8_t> bytes(data, size);
  proto::FrameReader reader;
  while (more()) {
    const proto::Decoded d = reader.next(std::size_t{1} << 20);
    if (d.status == proto::DecodeStatus::kBad) return;
    if (d.status == proto::DecodeStatus::kGood) {
      take(*d.message);
      continue;
    }
    if (bytes.empty()) return;
    const std::span<std::uint8_t> space = reader.space();
    const std::size_t n = std::min({space.size(), bytes.size(), kReadBytes});
    std::memcpy(space.data(), bytes.data(), n);
    reader.filled(n);
    bytes = bytes.subspan(n);
  }
}

}  // namespace glint::fuzz
