#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "proto/framing.h"

namespace glint::fuzz {

// Splits fuzz input into frames as a receiver would (a message that does not
// lie 8-aligned is verified in an aligned copy, as glintd's read buffer and
// the client's stream hold it) and gives each verified message to `take`
// while `more()` holds. Stops at the first bad or incomplete frame.
template <typename Take, typename More>
void forEachMessage(const std::uint8_t* data, std::size_t size, Take take, More more) {
  std::span<const std::uint8_t> bytes(data, size);
  std::vector<std::uint64_t> aligned;
  while (!bytes.empty() && more()) {
    const proto::Decoded d = proto::decodeFrame(bytes, std::size_t{1} << 20, aligned);
    if (d.status != proto::DecodeStatus::kGood) return;
    take(*d.message);
    bytes = bytes.subspan(d.consumed);
  }
}

}  // namespace glint::fuzz
