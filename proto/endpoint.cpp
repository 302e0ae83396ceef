#include "proto/endpoint.h"

#include <asio/ip/address.hpp>

#include "common/base/error.h"

namespace glint::proto {

asio::ip::tcp::endpoint parseEndpoint(const std::string& address, const std::string& option) {
  const auto colon = address.rfind(':');
  if (colon == std::string::npos || colon + 1 == address.size()) {
    throw InputError(option + " " + address + ": expected HOST:PORT, e.g. 127.0.0.1:7878");
  }
  std::string host = address.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  if (host == "localhost") host = "127.0.0.1";
  int port = -1;
  try {
    std::size_t used = 0;
    port = std::stoi(address.substr(colon + 1), &used);
    if (used != address.size() - colon - 1) port = -1;
  } catch (const std::exception&) {
    port = -1;
  }
  if (port < 0 || port > 65535) throw InputError(option + " " + address + ": the port must be in [0, 65535]");
  asio::error_code ec;
  const asio::ip::address ip = asio::ip::make_address(host, ec);
  if (ec) throw InputError(option + " " + address + ": '" + host + "' is not an IP address (" + ec.message() + ")");
  return {ip, static_cast<std::uint16_t>(port)};
}

std::string peerAddress(const asio::ip::tcp::socket::lowest_layer_type& socket, const std::string& fallback) {
  asio::error_code ec;
  const auto remote = socket.remote_endpoint(ec);
  return ec ? fallback : remote.address().to_string() + ":" + std::to_string(remote.port());
}

}  // namespace glint::proto
