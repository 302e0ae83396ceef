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

// --server values (each HOST:PORT[,HOST:PORT...], the option repeated) ->
// one server per address: a host name that resolves to several (a
// Kubernetes headless Service, DNS round robin) gives several. Duplicates
// are merged. Throws InputError naming the value that cannot be used.
std::vector<ServerAddress> resolveServers(const std::vector<std::string>& values);

}  // namespace glint
