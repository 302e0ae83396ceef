#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <memory>
#include <string>
#include <vector>

#include <asio.hpp>

#include "common/renderer.h"
#include "proto/framing.h"
#include "server/server.h"

namespace glint::server {

// One client: reads frames, answers them, queues tiles on the scheduler and
// writes results back, one write in flight. Lives on the I/O thread; work on
// the pool reaches it only through asio::post. Any problem with the bytes a
// client sends gets an Error back, and a connection that cannot go on is
// closed; nothing a client sends can stop the server or other clients.
class Connection : public std::enable_shared_from_this<Connection> {
 public:
  Connection(asio::ip::tcp::socket socket, ServerContext& context, std::uint64_t id);

  void start();
  // Cancels queued work and closes the socket; safe to call twice.
  void close(const std::string& why);

 private:
  // A frame set up by the client: the scene it renders and its renderer.
  struct Frame {
    std::shared_ptr<const PreparedScene> scene;
    std::unique_ptr<Renderer> renderer;
  };

  void readHeader();
  void readBody(std::uint32_t length);
  void readMore(std::uint32_t length);
  void onBody();
  void armTimer(std::chrono::milliseconds timeout, const char* what);
  void onTimer(const char* what);
  void handle(const wire::Message& message);
  void onHello(const wire::Hello& hello);
  void onSceneQuery(const wire::SceneQuery& query);
  void onSceneUpload(const wire::SceneUpload& upload);
  void onFrameSetup(const wire::FrameSetup& setup);
  void onTileRequest(const wire::TileRequest& tile);
  void deliver(std::vector<std::uint8_t> result);  // from a pool thread
  void send(std::vector<std::uint8_t> frame);
  void sendError(wire::ErrorCode code, const std::string& message, std::uint32_t frameId = 0,
                 std::uint32_t tileId = 0);
  void fail(wire::ErrorCode code, const std::string& message);  // error, then close
  void writeNext();

  asio::ip::tcp::socket socket_;
  asio::steady_timer timer_;
  ServerContext& context_;
  std::uint64_t id_;
  std::string peer_;
  std::array<std::uint8_t, proto::kHeaderBytes> header_{};
  std::vector<std::uint8_t> body_;
  std::deque<std::vector<std::uint8_t>> writes_;
  std::size_t queuedBytes_ = 0;
  std::size_t inFlight_ = 0;  // messages of writes_ in the current write
  bool writing_ = false;
  bool closeAfterWrites_ = false;
  bool closed_ = false;
  bool greeted_ = false;
  bool midMessage_ = false;  // a header arrived, its body has not yet
  std::chrono::steady_clock::time_point lastWrite_;
  int pending_ = 0;  // tiles and scene builds queued or running for this client
  std::map<std::uint32_t, std::shared_ptr<Frame>> frames_;
  std::mutex outboxMutex_;  // guards the four below
  std::vector<std::vector<std::uint8_t>> outbox_;  // finished tiles, not yet queued for writing
  std::size_t outboxBytes_ = 0;
  int untraced_ = 0;         // tiles submitted whose results are not in the outbox yet
  bool wakePosted_ = false;  // the I/O thread is already asked to take the outbox
};

}  // namespace glint::server
