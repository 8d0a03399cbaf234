#include "io/udp_receiver.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "io/input_error.hpp"

namespace conicloc::io {
namespace {

constexpr int kPollIntervalMs = 200;

double now_utc_s() {
  using namespace std::chrono;
  return duration<double>(system_clock::now().time_since_epoch()).count();
}

}  // namespace

UdpReceiver::UdpReceiver(std::uint16_t port, double idle_timeout_s)
    : port_(port), idle_timeout_s_(idle_timeout_s), buffer_(65536) {
  socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (socket_ < 0) throw InputError(name(), "socket", std::strerror(errno));
  const int yes = 1;
  ::setsockopt(socket_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  const int buffer_bytes = 8 << 20;  // ride out short stalls of the consumer
  ::setsockopt(socket_, SOL_SOCKET, SO_RCVBUF, &buffer_bytes, sizeof buffer_bytes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_ANY);
  address.sin_port = htons(port);
  if (::bind(socket_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(socket_);
    throw InputError(name(), "bind", reason);
  }
  socklen_t length = sizeof address;
  if (::getsockname(socket_, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
    port_ = ntohs(address.sin_port);
  }
}

UdpReceiver::~UdpReceiver() {
  if (socket_ >= 0) ::close(socket_);
}

std::string UdpReceiver::name() const {
  return "udp://:" + std::to_string(port_);
}

std::optional<UdpDatagram> UdpReceiver::next() {
  double waited_s = 0.0;
  while (!stopped_.load()) {
    pollfd descriptor{socket_, POLLIN, 0};
    const int ready = ::poll(&descriptor, 1, kPollIntervalMs);
    if (ready < 0 && errno != EINTR) throw InputError(name(), "poll", std::strerror(errno));
    if (ready <= 0) {
      waited_s += kPollIntervalMs * 1e-3;
      if (idle_timeout_s_ > 0 && waited_s >= idle_timeout_s_) return std::nullopt;
      continue;
    }
    sockaddr_in sender{};
    socklen_t sender_length = sizeof sender;
    const ssize_t bytes = ::recvfrom(socket_, buffer_.data(), buffer_.size(), 0,
                                     reinterpret_cast<sockaddr*>(&sender), &sender_length);
    if (bytes < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      throw InputError(name(), "recv", std::strerror(errno));
    }
    UdpDatagram datagram;
    datagram.payload =
        std::span<const std::uint8_t>(buffer_.data(), static_cast<std::size_t>(bytes));
    datagram.capture_time_s = now_utc_s();
    datagram.src_port = ntohs(sender.sin_port);
    datagram.dst_port = port_;
    datagram.record = ++count_;
    return datagram;
  }
  return std::nullopt;
}

}  // namespace conicloc::io
