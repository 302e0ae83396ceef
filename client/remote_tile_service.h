#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include <algorithm>
#include <memory>

#include "common/tile_service.h"
#include "proto/message_stream.h"
#include "proto/scene_bundle.h"

namespace glint {

// The tile interface over the network: a glintd holds the scene and fills
// the tiles. Connecting says Hello, asks whether the server holds the
// scene's hash and uploads the scene's bytes only when it does not. Errors
// name the server's address and say what went wrong.
class RemoteTileService : public TileService {
 public:
  struct Traffic {
    std::uint64_t bytesSent = 0;
    std::uint64_t bytesReceived = 0;
    bool uploaded = false;  // the scene had to be sent
    int serverThreads = 0;
  };

  RemoteTileService(const std::string& address, const proto::SceneBundle& bundle,
                    std::chrono::milliseconds timeout = std::chrono::seconds(60));
  ~RemoteTileService() override;

  void render(const FrameSettings& frame, std::span<const TileJob> jobs,
              const std::function<void(std::size_t, TileOutput&&)>& done) override;
  int parallelism() const override { return std::max(1, serverThreads_); }
  Traffic traffic() const {
    return {stream_->bytesSent(), stream_->bytesReceived(), uploaded_, serverThreads_};
  }

 private:
  void send(const std::vector<std::uint8_t>& frame);
  // The next message from the server (valid until the next receive); an
  // Error from the server is thrown.
  const wire::Message& receive();
  const wire::TileResult& receiveResult(std::uint32_t frameId, std::size_t requested,
                                       std::span<const std::size_t> tileBytes, std::vector<bool>& delivered);
  [[noreturn]] void fail(const std::string& what) const;

  std::string address_;
  std::unique_ptr<proto::MessageStream> stream_;
  std::size_t maxMessageBytes_ = proto::kDefaultMaxMessageBytes;
  proto::SceneHash hash_{};
  std::uint32_t nextFrame_ = 1;
  bool uploaded_ = false;
  int serverThreads_ = 0;
};

}  // namespace glint
