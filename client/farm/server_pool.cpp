#include "client/farm/server_pool.h"

#include <algorithm>

#include "common/base/error.h"

namespace glint {
namespace {

constexpr std::chrono::seconds kFirstRetry{1};  // a lost server is tried again after 1, 2, 4 ... s
constexpr std::chrono::seconds kLongestRetry{30};

}  // namespace

ServerPool::ServerPool(asio::io_context& io, std::vector<ServerAddress> addresses, const proto::SceneBundle& bundle,
                       const proto::BundleDigest& digest, const LinkTimeouts& timeouts, const proto::TlsFiles& tls,
                       LinkListener& listener)
    : io_(io), bundle_(bundle), digest_(digest), timeouts_(timeouts), listener_(listener) {
  if (tls.any()) {
    if (tls.ca.empty()) {
      throw InputError("--tls-cert and --tls-key need --tls-ca: the CA that signed the servers' certificates");
    }
    tls_.emplace(proto::clientTlsContext(tls));
  }
  adopt(addresses, 0);
}

void ServerPool::adopt(const std::vector<ServerAddress>& wanted, int frame) {
  for (const ServerAddress& address : wanted) {
    auto it = std::find_if(servers_.begin(), servers_.end(),
                           [&](const FarmServer& s) { return s.address.endpoint == address.endpoint; });
    if (it != servers_.end() && it->member) continue;
    if (it == servers_.end()) {
      FarmServer fresh;
      fresh.address = address;
      it = servers_.insert(servers_.end(), std::move(fresh));
    }
    it->member = true;
    it->joinedFrame = frame;
    it->failures = 0;
    it->report = {};
    connect(static_cast<std::size_t>(it - servers_.begin()));
  }
  for (FarmServer& s : servers_) {
    const bool wantedStill = std::any_of(wanted.begin(), wanted.end(),
                                         [&](const ServerAddress& a) { return a.endpoint == s.address.endpoint; });
    if (!s.member || wantedStill) continue;
    s.member = false;
    s.leftFrame = frame;
    s.link->close();
    s.report.state = ServerState::kLeft;
    s.report.why = "no longer listed: sent Goodbye";
  }
}

void ServerPool::connect(std::size_t index) {
  FarmServer& s = servers_[index];
  if (s.link) s.link->detach();
  s.everReady = false;
  std::unique_ptr<proto::ByteStream> stream =
      tls_ ? proto::connectingTlsStream(io_, s.address.endpoint, *tls_, s.address.host)
           : proto::connectingStream(io_, s.address.endpoint);
  s.link = std::make_shared<ServerLink>(io_, std::move(stream), index, s.address.name, bundle_, digest_, timeouts_);
  s.link->start(listener_);
}

void ServerPool::closeAll() {
  for (FarmServer& s : servers_) {
    if (s.member) s.link->close();
  }
}

void ServerPool::retryLost() {
  const auto now = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < servers_.size(); ++i) {
    if (servers_[i].member && servers_[i].link->failed() && now >= servers_[i].retryAt) connect(i);
  }
}

void ServerPool::ready(std::size_t index) {
  FarmServer& s = servers_[index];
  s.everReady = true;
  s.failures = 0;
  s.busySince.reset();
  s.report.state = ServerState::kOk;
  s.report.why.clear();
}

void ServerPool::failed(std::size_t index, const LinkFailure& failure) {
  FarmServer& s = servers_[index];
  if (!s.member) return;
  s.report.state = s.everReady ? ServerState::kLost : ServerState::kUnreachable;
  s.report.why = failure.what;
  ++s.failures;
  const auto now = std::chrono::steady_clock::now();
  const auto backoff = std::min<std::chrono::seconds>(kFirstRetry * (1 << std::min(s.failures - 1, 5)), kLongestRetry);
  s.retryAt = now + backoff;
  if (failure.kind != LinkFailure::Kind::kBusy) {
    s.busySince.reset();
  } else if (!s.busySince) {
    s.busySince = now;
  }
}

std::optional<std::chrono::steady_clock::time_point> ServerPool::nextBusyRetry(
    std::chrono::milliseconds patience) const {
  std::optional<std::chrono::steady_clock::time_point> next;
  for (const FarmServer& s : servers_) {
    if (!s.member || !s.busySince || !s.link->failed() || s.retryAt > *s.busySince + patience) continue;
    if (!next || s.retryAt < *next) next = s.retryAt;
  }
  return next;
}

std::size_t ServerPool::members() const {
  return static_cast<std::size_t>(
      std::count_if(servers_.begin(), servers_.end(), [](const FarmServer& s) { return s.member; }));
}

std::size_t ServerPool::up() const {
  return static_cast<std::size_t>(
      std::count_if(servers_.begin(), servers_.end(), [](const FarmServer& s) { return s.member && s.link->ready(); }));
}

bool ServerPool::anyConnecting() const {
  return std::any_of(servers_.begin(), servers_.end(),
                     [](const FarmServer& s) { return s.member && !s.link->ready() && !s.link->failed(); });
}

bool ServerPool::anyUploaded() const {
  return std::any_of(servers_.begin(), servers_.end(), [](const FarmServer& s) { return s.link->uploaded(); });
}

int ServerPool::threadsUp() const {
  int threads = 0;
  for (const FarmServer& s : servers_) threads += s.member && s.link->ready() ? s.link->threads() : 0;
  return threads;
}

std::string ServerPool::states() const {
  std::string lines;
  for (const FarmServer& s : servers_) {
    if (!s.member) continue;
    lines += "\n  server " + s.address.name + ": " + std::string(enumWord(s.report.state)) + ", " + s.report.why;
  }
  return lines;
}

}  // namespace glint
