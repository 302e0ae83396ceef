#include "client/farm/server_source.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "common/base/error.h"

namespace glint {
namespace {

// The file's whole text; InputError when it cannot be read.
std::string readServerFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("--server-file " + path + ": cannot be read (does it exist, and may glint read it?)");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The same servers, in any order.
bool sameEndpoints(const std::vector<ServerAddress>& a, const std::vector<ServerAddress>& b) {
  const auto endpoints = [](const std::vector<ServerAddress>& list) {
    std::vector<asio::ip::tcp::endpoint> out;
    for (const ServerAddress& s : list) out.push_back(s.endpoint);
    std::sort(out.begin(), out.end());
    return out;
  };
  return endpoints(a) == endpoints(b);
}

}  // namespace

ServerSource::ServerSource(std::vector<ServerAddress> addresses) : addresses_(std::move(addresses)) {}

ServerSource::ServerSource(std::vector<std::string> values, std::string file, Clock::time_point now, Resolve resolve)
    : values_(std::move(values)), file_(std::move(file)), resolve_(std::move(resolve)) {
  if (!file_.empty()) fileText_ = readServerFile(file_);
  addresses_ = resolve_(entries(fileText_));
  resolvedAt_ = now;
  if (addresses_.empty()) {
    throw InputError(file_.empty() ? "--server: no address given"
                                   : "--server-file " + file_ + ": lists no server (one HOST:PORT a line)");
  }
}

std::vector<ServerEntry> ServerSource::entries(const std::string& fileText) const {
  std::vector<ServerEntry> out;
  for (const std::string& value : values_) out.push_back({value, "--server"});
  if (!file_.empty()) {
    for (ServerEntry& e : parseServerFile(fileText, "--server-file " + file_)) out.push_back(std::move(e));
  }
  return out;
}

bool ServerSource::refresh(Clock::time_point now) {
  if (values_.empty() && file_.empty()) return false;  // a fixed set
  std::string text = fileText_;
  try {
    if (!file_.empty()) text = readServerFile(file_);
    if (text == fileText_ && now - resolvedAt_ < kResolveEvery) return false;
    std::vector<ServerAddress> addresses = resolve_(entries(text));
    if (addresses.empty()) throw InputError("--server-file " + file_ + " lists no server");
    fileText_ = std::move(text);
    resolvedAt_ = now;
    warning_.clear();
    const bool changed = !sameEndpoints(addresses, addresses_);
    addresses_ = std::move(addresses);
    return changed;
  } catch (const InputError& e) {
    fileText_ = std::move(text);  // tried: not again before kResolveEvery unless the file changes
    resolvedAt_ = now;
    const std::size_t n = addresses_.size();
    warning_ = std::string(e.what()) + "; the farm stays as it was (" + std::to_string(n) +
               (n == 1 ? " server)" : " servers)");
    return false;
  }
}

}  // namespace glint
