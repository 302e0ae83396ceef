#include "tests/support/message_stream.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace glint::proto {

MessageStream::MessageStream(const asio::ip::tcp::endpoint& endpoint, std::chrono::milliseconds timeout)
    : timeout_(timeout), socket_(io_) {
  asio::error_code error;
  bool done = false;
  socket_.async_connect(endpoint, [&](const asio::error_code& e) {
    error = e;
    done = true;
  });
  if (!runUntil(done)) throw StreamError(StreamError::Kind::kTimeout, "cannot connect (timed out)");
  if (error) {
    close();
    throw StreamError(StreamError::Kind::kIo, "cannot connect (" + error.message() + ")");
  }
  socket_.set_option(asio::ip::tcp::no_delay(true), error);
}

bool MessageStream::runUntil(const bool& done) {
  io_.restart();
  const auto deadline = std::chrono::steady_clock::now() + timeout_;
  while (!done && std::chrono::steady_clock::now() < deadline) io_.run_one_until(deadline);
  if (done) return true;
  // Timed out: cancel the operation and let its handler run.
  asio::error_code ignored;
  socket_.cancel(ignored);
  io_.restart();
  while (!done && io_.run_one() > 0) {
  }
  return false;
}

void MessageStream::close() {
  asio::error_code ignored;
  socket_.close(ignored);
}

void MessageStream::send(std::span<const std::uint8_t> bytes) {
  asio::error_code error;
  bool done = false;
  asio::async_write(socket_, asio::buffer(bytes.data(), bytes.size()), [&](const asio::error_code& e, std::size_t) {
    error = e;
    done = true;
  });
  if (!runUntil(done)) throw StreamError(StreamError::Kind::kTimeout, "sending timed out");
  if (error) throw StreamError(StreamError::Kind::kIo, "sending failed (" + error.message() + ")");
  sent_ += bytes.size();
}

const wire::Message& MessageStream::receive() {
  while (true) {
    const std::span<const std::uint8_t> unread(buffer_.data() + consumed_, buffer_.size() - consumed_);
    const Decoded d = decodeFrame(unread, kDefaultMaxMessageBytes, aligned_);
    if (d.status == DecodeStatus::kBad) throw StreamError(StreamError::Kind::kBadMessage, "bad message: " + d.error);
    if (d.status == DecodeStatus::kGood) {
      consumed_ += d.consumed;
      received_ += d.consumed;
      return *d.message;  // in buffer_ or aligned_, both untouched until the next receive()
    }
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(consumed_));
    consumed_ = 0;
    constexpr std::size_t kMaxWatermark = 64 * 1024;
    const std::size_t promised = expected_ > buffer_.size() ? expected_ - buffer_.size() : 1;
    const int watermark = static_cast<int>(std::clamp<std::size_t>(promised, 1, kMaxWatermark));
    if (watermark != lowWatermark_) {
      asio::error_code ignored;  // without it, reads just wake more often
      socket_.set_option(asio::socket_base::receive_low_watermark(watermark), ignored);
      lowWatermark_ = watermark;
    }
    std::array<std::uint8_t, 65536> chunk;
    asio::error_code error;
    std::size_t got = 0;
    bool done = false;
    socket_.async_read_some(asio::buffer(chunk), [&](const asio::error_code& e, std::size_t n) {
      error = e;
      got = n;
      done = true;
    });
    if (!runUntil(done)) {
      throw StreamError(StreamError::Kind::kTimeout,
                        "no answer within " + std::to_string(timeout_.count()) + " ms");
    }
    if (error == asio::error::eof || error == asio::error::connection_reset) {
      throw StreamError(StreamError::Kind::kClosed, "closed the connection");
    }
    if (error) throw StreamError(StreamError::Kind::kIo, "receiving failed (" + error.message() + ")");
    buffer_.insert(buffer_.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(got));
  }
}

}  // namespace glint::proto
