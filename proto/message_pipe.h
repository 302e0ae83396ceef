#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <asio.hpp>

#include "proto/byte_stream.h"
#include "proto/frame_reader.h"
#include "proto/write_queue.h"

namespace glint::proto {

// What a pipe tells the end that owns it, on the thread running its I/O.
class PipeOwner {
 public:
  virtual ~PipeOwner() = default;
  // Messages are read and handed on while this holds (asked before each read
  // and between messages).
  virtual bool listening() const = 0;
  // The largest message taken now.
  virtual std::size_t messageLimit() const = 0;
  virtual void received(const wire::Message& message) = 0;
  // A message that does not decode (its code and reason in `bad`); the pipe
  // reads no further.
  virtual void refused(const Decoded& bad) = 0;
  virtual void readFailed(const asio::error_code& error) = 0;
  // After a read's whole messages were handed on, before the next read:
  // `wasMid`, part of a message was held before its bytes; `took`, whole
  // messages came.
  virtual void afterRead(bool /*wasMid*/, bool /*took*/) {}
  // A write of `bytes` finished; a failed one, instead, writeFailed.
  virtual void wrote(std::size_t /*bytes*/) {}
  virtual void writeFailed(const asio::error_code& error) = 0;
  // Nothing is left to write.
  virtual void drained() {}
};

// One end of a framed conversation on a ByteStream (plain TCP or TLS), the
// one shape both ends of the wire move messages with (glintd's Connection,
// glint's ServerLink): it reads whole messages and hands them to its owner
// in order, writes the owner's messages one write at a time (gathering those
// queued meanwhile, up to `gatherBytes` a write) and counts the bytes each
// way. What a message means, when to time out and when to close are the
// owner's. A member of its owner: each read and write in flight holds the
// owner (through the pointer given to start) until its handler has run.
class MessagePipe {
 public:
  MessagePipe(std::unique_ptr<ByteStream> stream, std::size_t gatherBytes)
      : stream_(std::move(stream)), gatherBytes_(gatherBytes) {}
  MessagePipe(const MessagePipe&) = delete;
  MessagePipe& operator=(const MessagePipe&) = delete;

  // The owner, kept alive by the handlers in flight. Before read() or send().
  void start(const std::shared_ptr<PipeOwner>& owner) { owner_ = owner; }
  ByteStream& stream() { return *stream_; }

  // Reads on until the owner stops listening or the stream fails.
  void read();
  void send(std::vector<std::uint8_t> frame);

  bool midMessage() const { return reader_.midMessage(); }
  bool writing() const { return writes_.writing(); }
  std::size_t queuedBytes() const { return writes_.queuedBytes(); }
  std::chrono::steady_clock::time_point lastWrite() const { return lastWrite_; }
  std::uint64_t bytesSent() const { return sent_; }
  std::uint64_t bytesReceived() const { return received_; }

 private:
  void onRead(const std::shared_ptr<PipeOwner>& owner, const asio::error_code& error, std::size_t n);
  void writeNext();

  std::unique_ptr<ByteStream> stream_;
  std::size_t gatherBytes_;
  std::weak_ptr<PipeOwner> owner_;
  FrameReader reader_;
  WriteQueue writes_;
  std::chrono::steady_clock::time_point lastWrite_;
  std::uint64_t sent_ = 0;
  std::uint64_t received_ = 0;
};

}  // namespace glint::proto
