#include "proto/frame_reader.h"

#include <algorithm>
#include <cstring>

namespace glint::proto {

std::span<std::uint8_t> FrameReader::space() {
  const std::size_t held = end_ - begin_;
  if (held == 0 && buffer_.size() > kReadChunkBytes) std::vector<std::uint8_t>().swap(buffer_);
  if (begin_ > 0) {  // the partial message to the front
    std::memmove(buffer_.data(), buffer_.data() + begin_, held);
    begin_ = 0;
    end_ = held;
  }
  if (end_ == buffer_.size()) buffer_.resize(buffer_.size() + std::max(kReadChunkBytes, held));
  return {buffer_.data() + end_, buffer_.size() - end_};
}

void FrameReader::filled(std::size_t n) {
  end_ = std::min(end_ + n, buffer_.size());
}

Decoded FrameReader::next(std::size_t maxMessageBytes) {
  Decoded d = decodeFrame({buffer_.data() + begin_, end_ - begin_}, maxMessageBytes, aligned_);
  if (d.status == DecodeStatus::kGood) begin_ += d.consumed;
  return d;
}

}  // namespace glint::proto
