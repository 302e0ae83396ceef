#pragma once

#include <string>

#include <asio/ip/tcp.hpp>

namespace glint::proto {

// "HOST:PORT" (IPv4, "[IPv6]" or localhost) -> endpoint; throws InputError
// naming `option` ("--server 10.0.0.2: expected HOST:PORT ...").
asio::ip::tcp::endpoint parseEndpoint(const std::string& address, const std::string& option);

// The address of the other end of a connected socket ("10.0.0.2:51234"),
// or `fallback` where it has none.
std::string peerAddress(const asio::ip::tcp::socket::lowest_layer_type& socket, const std::string& fallback);

}  // namespace glint::proto
