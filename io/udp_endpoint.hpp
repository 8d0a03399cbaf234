#pragma once
// An IPv4 UDP endpoint as given on the command line: "[ADDR:]PORT" to listen on (ADDR defaults
// to every local address), "HOST:PORT" to send to. HOST may be a dotted quad or a name
// (resolved once, IPv4 only).
//
// Example:
//   auto listen = io::parse_listen_endpoint("127.0.0.1:2368");   // {"127.0.0.1", 2368}
//   auto target = io::parse_send_endpoint("localhost:9000");
//   sockaddr_in address = io::socket_address(target);

#include <netinet/in.h>

#include <cstdint>
#include <string>

namespace conicloc::io {

struct UdpEndpoint {
  std::string host;  ///< "" (listen only): every local address
  std::uint16_t port = 0;
};

/// "[ADDR:]PORT"; PORT 0 asks the system for a free port. Throws InputError naming `flag`.
UdpEndpoint parse_listen_endpoint(const std::string& text, const std::string& flag = "--udp");
/// "HOST:PORT" with PORT > 0. Throws InputError naming `flag`.
UdpEndpoint parse_send_endpoint(const std::string& text, const std::string& flag);

/// The socket address of `endpoint` (host resolved to IPv4). Throws InputError when the host
/// does not resolve.
sockaddr_in socket_address(const UdpEndpoint& endpoint);

/// "ADDR:PORT" of an IPv4 socket address (network byte order inside `address`).
std::string address_text(const sockaddr_in& address);

}  // namespace conicloc::io
