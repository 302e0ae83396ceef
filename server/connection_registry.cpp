#include "server/connection_registry.h"

#include <algorithm>

namespace glint::server {

void ConnectionRegistry::addWaiting(std::uint64_t id,
                                    const std::shared_ptr<ConnectionHandle>& connection) {
  while (waiting_.size() >= maxWaiting_ &&
         dropOldestWaiting("dropped: too many connections waiting for Hello")) {
  }
  waiting_[id] = connection;
}

bool ConnectionRegistry::admit(std::uint64_t id, Clock::time_point now) {
  const auto it = waiting_.find(id);
  if (it == waiting_.end()) return false;
  if (clients_.size() >= maxClients_ && !evictIdlest(now)) return false;
  clients_[id] = Client{it->second, now};
  waiting_.erase(it);
  return true;
}

void ConnectionRegistry::worked(std::uint64_t id, Clock::time_point now) {
  const auto it = clients_.find(id);
  if (it != clients_.end()) it->second.lastWork = now;
}

bool ConnectionRegistry::evictIdlest(Clock::time_point now) {
  const auto idlest = std::min_element(
      clients_.begin(), clients_.end(),
      [](const auto& a, const auto& b) { return a.second.lastWork < b.second.lastWork; });
  if (idlest == clients_.end() || now - idlest->second.lastWork < kIdleBeforeEviction) return false;
  const std::shared_ptr<ConnectionHandle> connection = idlest->second.connection.lock();
  clients_.erase(idlest);
  if (connection) connection->close("dropped: idle while a new client wanted its place");
  return true;
}

void ConnectionRegistry::remove(std::uint64_t id) {
  waiting_.erase(id);
  clients_.erase(id);
}

bool ConnectionRegistry::dropOldestWaiting(const std::string& why) {
  if (waiting_.empty()) return false;
  const std::shared_ptr<ConnectionHandle> oldest = waiting_.begin()->second.lock();
  waiting_.erase(waiting_.begin());
  if (oldest) oldest->close(why);
  return true;
}

void ConnectionRegistry::closeAll(const std::string& why) {
  Pool all;
  all.swap(waiting_);
  for (auto& [id, client] : clients_) all[id] = client.connection;
  clients_.clear();
  for (auto& [id, weak] : all) {
    if (const auto connection = weak.lock()) connection->close(why);
  }
}

}  // namespace glint::server
