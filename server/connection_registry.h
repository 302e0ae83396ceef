#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace glint::server {

// What the registry needs of a connection, whatever its stream type.
class ConnectionHandle {
 public:
  virtual ~ConnectionHandle() = default;
  // Cancels its queued work and closes it; safe to call twice.
  virtual void close(const std::string& why) = 0;
};

// Who is connected, in two pools: connections that have not said Hello yet
// (a larger pool, oldest dropped first when it is full, so that silent
// connections can never lock real clients out) and clients that have (at
// most maxClients). The clients' places go to clients that work: when they
// are full, a new client takes the place of the one that has asked for work
// (an upload, a tile) least recently, if that was kIdleBeforeEviction ago or
// more (its Hello counts as its first work; a query or a keep-alive does
// not); otherwise it gets Busy. Lives on the I/O thread.
class ConnectionRegistry {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::seconds kIdleBeforeEviction{1};

  ConnectionRegistry(std::size_t maxClients, std::size_t maxWaiting)
      : maxClients_(maxClients), maxWaiting_(maxWaiting) {}

  // A new connection waits for its Hello; when the waiting pool is full, the
  // oldest waiting connection is closed to make room.
  void addWaiting(std::uint64_t id, const std::shared_ptr<ConnectionHandle>& connection);
  // Moves a connection that said Hello to the clients, closing the client
  // idle longest to make room if the places are full; false when none has
  // been idle kIdleBeforeEviction (the connection stays where it was).
  bool admit(std::uint64_t id, Clock::time_point now = Clock::now());
  // A client asked for work: it keeps its place.
  void worked(std::uint64_t id, Clock::time_point now = Clock::now());
  // Forgets a connection that closed.
  void remove(std::uint64_t id);
  // Closes the oldest waiting connection; false when none waits.
  bool dropOldestWaiting(const std::string& why);
  // Closes every connection.
  void closeAll(const std::string& why);

  std::size_t clients() const { return clients_.size(); }
  std::size_t waiting() const { return waiting_.size(); }
  std::size_t maxClients() const { return maxClients_; }

 private:
  using Pool = std::map<std::uint64_t, std::weak_ptr<ConnectionHandle>>;  // by id: accept order
  struct Client {
    std::weak_ptr<ConnectionHandle> connection;
    Clock::time_point lastWork;
  };
  // Closes the client idle longest if it has been idle long enough.
  bool evictIdlest(Clock::time_point now);
  std::size_t maxClients_;
  std::size_t maxWaiting_;
  Pool waiting_;
  std::map<std::uint64_t, Client> clients_;
};

}  // namespace glint::server
