#include "io/udp_endpoint.hpp"

#include <arpa/inet.h>
#include <netdb.h>
#include <sys/socket.h>

#include <charconv>

#include "io/input_error.hpp"

namespace conicloc::io {
namespace {

std::uint16_t parse_port(const std::string& text, const std::string& whole,
                         const std::string& flag) {
  unsigned value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() || value > 65535) {
    throw InputError(flag, "'" + whole + "'", "'" + text + "' is not a UDP port (0-65535)");
  }
  return static_cast<std::uint16_t>(value);
}

}  // namespace

UdpEndpoint parse_listen_endpoint(const std::string& text, const std::string& flag) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos) return {"", parse_port(text, text, flag)};
  UdpEndpoint endpoint{text.substr(0, colon), parse_port(text.substr(colon + 1), text, flag)};
  socket_address(endpoint);  // a bad address is reported now, naming the flag's text
  return endpoint;
}

UdpEndpoint parse_send_endpoint(const std::string& text, const std::string& flag) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0) {
    throw InputError(flag, "'" + text + "'", "expected HOST:PORT");
  }
  UdpEndpoint endpoint{text.substr(0, colon), parse_port(text.substr(colon + 1), text, flag)};
  if (endpoint.port == 0) throw InputError(flag, "'" + text + "'", "port 0 cannot be sent to");
  socket_address(endpoint);
  return endpoint;
}

sockaddr_in socket_address(const UdpEndpoint& endpoint) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(endpoint.port);
  if (endpoint.host.empty()) {
    address.sin_addr.s_addr = htonl(INADDR_ANY);
    return address;
  }
  if (::inet_pton(AF_INET, endpoint.host.c_str(), &address.sin_addr) == 1) return address;
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  const int error = ::getaddrinfo(endpoint.host.c_str(), nullptr, &hints, &found);
  if (error != 0 || found == nullptr) {
    throw InputError(
        endpoint.host, "host",
        std::string("not an IPv4 address or host name (") + ::gai_strerror(error) + ")");
  }
  address.sin_addr = reinterpret_cast<const sockaddr_in*>(found->ai_addr)->sin_addr;
  ::freeaddrinfo(found);
  return address;
}

std::string address_text(const sockaddr_in& address) {
  char text[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &address.sin_addr, text, sizeof text);
  return std::string(text) + ":" + std::to_string(ntohs(address.sin_port));
}

}  // namespace conicloc::io
