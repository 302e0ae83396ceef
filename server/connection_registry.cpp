#include "server/connection_registry.h"


namespace glint::server {

void ConnectionRegistry::addWaiting(std::uint64_t id, const std::shared_ptr<ConnectionHandle>& connection) {
  while (waiting_.size() >= maxWaiting_ && dropOldestWaiting("dropped: too many connections waiting for Hello")) {
  }
  waiting_[id] = connection;
}

bool ConnectionRegistry::admit(std::uint64_t id) {
  const auto it = waiting_.find(id);
  if (it == waiting_.end() || clients_.size() >= maxClients_) return false;
  clients_.insert(waiting_.extract(it));
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
  all.merge(clients_);
  clients_.clear();
  for (auto& [id, weak] : all) {
    if (const auto connection = weak.lock()) connection->close(why);
  }
}

}  // namespace glint::server
