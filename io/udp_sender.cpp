#include "io/udp_sender.hpp"

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "io/input_error.hpp"

namespace conicloc::io {

UdpSender::UdpSender(const UdpEndpoint& to) : to_(to), address_(socket_address(to)) {
  socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (socket_ < 0) throw InputError(name(), "socket", std::strerror(errno));
}

UdpSender::~UdpSender() {
  if (socket_ >= 0) ::close(socket_);
}

bool UdpSender::send(std::span<const std::uint8_t> payload) {
  const ssize_t sent = ::sendto(socket_, payload.data(), payload.size(), 0,
                                reinterpret_cast<const sockaddr*>(&address_), sizeof address_);
  return sent == static_cast<ssize_t>(payload.size());
}

bool UdpSender::send(const std::string& text) {
  return send(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

std::string UdpSender::name() const {
  return "udp://" + to_.host + ":" + std::to_string(to_.port);
}

}  // namespace conicloc::io
