#include "client/farm/server_list.h"

#include <algorithm>
#include <optional>
#include <sstream>

#include <asio.hpp>

#include "common/base/error.h"
#include "common/base/printable.h"

namespace glint {
namespace {

// "HOST:PORT", "[V6]:PORT" -> host and port, or nothing when it is neither.
std::optional<std::pair<std::string, std::string>> parseHostPort(const std::string& value) {
  const auto colon = value.rfind(':');
  if (colon == std::string::npos) return std::nullopt;
  const std::string port = value.substr(colon + 1);
  std::string host = value.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  const bool digits = !port.empty() && port.size() <= 5 && std::all_of(port.begin(), port.end(), ::isdigit);
  if (host.empty() || !digits || std::stoi(port) > 65535) return std::nullopt;
  return std::pair{host, port};
}

// Entries come from a file too: their text reaches the terminal escaped.
std::string notHostPort(const std::string& value) {
  return printable(value) + ": expected HOST:PORT, e.g. 127.0.0.1:7878 (several: A:P,B:P)";
}

// "HOST:PORT" -> host and port, or InputError naming where it came from.
std::pair<std::string, std::string> splitHostPort(const std::string& value, const std::string& origin) {
  std::optional<std::pair<std::string, std::string>> parts = parseHostPort(value);
  if (!parts) throw InputError(origin + " " + notHostPort(value));
  return *parts;
}

// The addresses of one HOST:PORT: its IPv4 addresses where it has any (so
// that "localhost" is one server, not also a ::1 that glintd may not listen
// on), else its IPv6 ones.
std::vector<ServerAddress> resolveOne(asio::ip::tcp::resolver& resolver, const std::string& value,
                                      const std::string& origin) {
  const auto [host, port] = splitHostPort(value, origin);
  asio::error_code error;
  auto results = resolver.resolve(asio::ip::tcp::v4(), host, port, error);
  if (error) results = resolver.resolve(host, port, error);
  if (error) {
    throw InputError(origin + " " + printable(value) + ": cannot resolve '" + printable(host) + "' (" +
                     error.message() + ")");
  }
  std::vector<ServerAddress> out;
  for (const auto& entry : results) out.push_back({value, host, entry.endpoint()});
  if (out.size() > 1) {
    for (ServerAddress& a : out) a.name = value + " (" + a.endpoint.address().to_string() + ")";
  }
  return out;
}

}  // namespace

std::vector<ServerAddress> resolveEntries(const std::vector<ServerEntry>& entries) {
  asio::io_context io;
  asio::ip::tcp::resolver resolver(io);
  std::vector<ServerAddress> servers;
  for (const ServerEntry& entry : entries) {
    std::stringstream list(entry.value);
    std::string item;
    while (std::getline(list, item, ',')) {
      if (item.empty()) continue;
      for (ServerAddress& a : resolveOne(resolver, item, entry.origin)) {
        const bool seen = std::any_of(servers.begin(), servers.end(),
                                      [&a](const ServerAddress& s) { return s.endpoint == a.endpoint; });
        if (!seen) servers.push_back(std::move(a));
      }
    }
  }
  return servers;
}

std::string hostPortListProblem(const std::string& value) {
  std::stringstream list(value);
  std::string item;
  while (std::getline(list, item, ',')) {
    if (!item.empty() && !parseHostPort(item)) return notHostPort(item);
  }
  return "";
}

std::vector<ServerAddress> resolveServers(const std::vector<std::string>& values) {
  std::vector<ServerEntry> entries;
  for (const std::string& value : values) entries.push_back({value, "--server"});
  std::vector<ServerAddress> servers = resolveEntries(entries);
  if (servers.empty()) throw InputError("--server: no address given");
  return servers;
}

std::vector<ServerEntry> parseServerFile(const std::string& text, const std::string& path) {
  std::vector<ServerEntry> entries;
  std::stringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    line = line.substr(0, line.find('#'));
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    const auto last = line.find_last_not_of(" \t\r");
    entries.push_back({line.substr(first, last - first + 1), path + ":" + std::to_string(number)});
  }
  return entries;
}

}  // namespace glint
