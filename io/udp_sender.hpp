#pragma once
// Sends datagrams to one IPv4 UDP endpoint (poses to a consumer, a capture's packets to a
// receiver). Sending never waits for the receiver; a datagram nobody listens for is lost, as UDP
// is.
//
// Example:
//   io::UdpSender sender(io::parse_send_endpoint("127.0.0.1:9000", "--pose-udp"));
//   sender.send(bytes);

#include <cstdint>
#include <span>
#include <string>

#include "io/udp_endpoint.hpp"

namespace conicloc::io {

class UdpSender {
 public:
  /// Throws InputError when the host does not resolve or no socket can be made.
  explicit UdpSender(const UdpEndpoint& to);
  ~UdpSender();
  UdpSender(const UdpSender&) = delete;
  UdpSender& operator=(const UdpSender&) = delete;

  /// Sends one datagram. False when the system refused it (e.g. nobody listens on loopback and
  /// an earlier datagram came back as ICMP "port unreachable"); the caller may count that.
  bool send(std::span<const std::uint8_t> payload);
  bool send(const std::string& text);
  /// "udp://HOST:PORT".
  std::string name() const;

 private:
  UdpEndpoint to_;
  sockaddr_in address_{};
  int socket_ = -1;
};

}  // namespace conicloc::io
