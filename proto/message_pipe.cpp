#include "proto/message_pipe.h"

namespace glint::proto {

void MessagePipe::read() {
  const std::shared_ptr<PipeOwner> owner = owner_.lock();
  if (!owner || !owner->listening()) return;
  const std::span<std::uint8_t> space = reader_.space();
  stream_->readSome(asio::buffer(space.data(), space.size()),
                    [this, owner](const asio::error_code& error, std::size_t n) { onRead(owner, error, n); });
}

// Hands every whole message that arrived to the owner, in order, then reads on.
void MessagePipe::onRead(const std::shared_ptr<PipeOwner>& owner, const asio::error_code& error, std::size_t n) {
  if (!owner->listening()) return;
  if (error) return owner->readFailed(error);
  received_ += n;
  const bool wasMid = reader_.midMessage();
  reader_.filled(n);
  bool took = false;
  while (owner->listening()) {
    const Decoded d = reader_.next(owner->messageLimit());
    if (d.status == DecodeStatus::kNeedMore) break;
    if (d.status == DecodeStatus::kBad) return owner->refused(d);
    took = true;
    owner->received(*d.message);
  }
  if (!owner->listening()) return;
  owner->afterRead(wasMid, took);
  read();
}

void MessagePipe::send(std::vector<std::uint8_t> frame) {
  writes_.push(std::move(frame));
  if (!writes_.writing()) writeNext();
}

// One write in flight, gathering what was queued meanwhile.
void MessagePipe::writeNext() {
  const std::shared_ptr<PipeOwner> owner = owner_.lock();
  if (!owner || !stream_->isOpen()) return;
  std::vector<asio::const_buffer> buffers;
  for (const auto& frame : writes_.next(gatherBytes_)) buffers.push_back(asio::buffer(frame.data(), frame.size()));
  if (buffers.empty()) return owner->drained();
  lastWrite_ = std::chrono::steady_clock::now();
  stream_->write(buffers, [this, owner](const asio::error_code& error, std::size_t n) {
    sent_ += n;
    writes_.written();
    if (error) return owner->writeFailed(error);
    owner->wrote(n);
    writeNext();
  });
}

}  // namespace glint::proto
