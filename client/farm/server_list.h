#pragma once

#include <string>
#include <vector>

#include <asio/ip/tcp.hpp>

namespace glint {

// One glintd to render through: how the user named it, and where it is.
struct ServerAddress {
  std::string name;  // "10.0.0.2:7878", or "render.farm:7878 (10.0.0.2)" for one of a name's addresses
  std::string host;  // as dialled, "10.0.0.2" or "render.farm": a TLS server's certificate must name it
  asio::ip::tcp::endpoint endpoint;
};

// Servers as the user wrote them: HOST:PORT[,HOST:PORT...], and where, for
// errors ("--server", "farm.txt:3").
struct ServerEntry {
  std::string value;
  std::string origin;
};

// The entries -> one server per address: a host name that resolves to
// several (a Kubernetes headless Service, DNS round robin) gives several.
// Duplicates are merged. Throws InputError naming the entry that cannot be
// used; an empty result is not an error here.
std::vector<ServerAddress> resolveEntries(const std::vector<ServerEntry>& entries);

// Why a HOST:PORT[,HOST:PORT...] value is malformed, or "" when every item
// is HOST:PORT (checked before any name is resolved: a usage error).
std::string hostPortListProblem(const std::string& value);

// --server values (the option repeated) -> servers, as resolveEntries; none is an
// InputError.
std::vector<ServerAddress> resolveServers(const std::vector<std::string>& values);

// A --server-file's text -> its entries: one HOST:PORT a line; blank lines
// and what follows a '#' are ignored.
std::vector<ServerEntry> parseServerFile(const std::string& text, const std::string& path);

}  // namespace glint
