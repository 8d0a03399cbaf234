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

UdpReceiver::UdpReceiver(const UdpReceiverConfig& config)
    : host_(config.listen.host), idle_timeout_s_(config.idle_timeout_s), buffer_(65536) {
  port_ = config.listen.port;
  socket_ = bind_socket(config.listen.port, port_);
  if (config.position_port) {
    std::uint16_t bound = *config.position_port;
    try {
      position_socket_ = bind_socket(*config.position_port, bound);
    } catch (...) {
      ::close(socket_);
      throw;
    }
    position_port_ = bound;
  }
}

UdpReceiver::UdpReceiver(std::uint16_t port, double idle_timeout_s)
    : UdpReceiver(UdpReceiverConfig{
          .listen = {"", port}, .position_port = std::nullopt, .idle_timeout_s = idle_timeout_s}) {}

UdpReceiver::~UdpReceiver() {
  if (socket_ >= 0) ::close(socket_);
  if (position_socket_ >= 0) ::close(position_socket_);
}

int UdpReceiver::bind_socket(std::uint16_t port, std::uint16_t& bound_port) const {
  const std::string where = "udp://" + host_ + ":" + std::to_string(port);
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) throw InputError(where, "socket", std::strerror(errno));
  // No SO_REUSEADDR: with it, a second listener (another localize, or --udp P --position-port P)
  // binds the same UDP port without error and the two silently split the datagrams.
  const int buffer_bytes = 8 << 20;  // ride out short stalls of the consumer
  ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &buffer_bytes, sizeof buffer_bytes);
  sockaddr_in address = socket_address({host_, port});
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    throw InputError(where, "bind", reason);
  }
  socklen_t length = sizeof address;
  bound_port = port;
  if (::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
    bound_port = ntohs(address.sin_port);
  }
  return fd;
}

std::string UdpReceiver::name() const {
  return "udp://" + host_ + ":" + std::to_string(port_);
}

std::optional<UdpDatagram> UdpReceiver::receive(int socket, std::uint16_t port) {
  sockaddr_in sender{};
  socklen_t sender_length = sizeof sender;
  const ssize_t bytes = ::recvfrom(socket, buffer_.data(), buffer_.size(), 0,
                                   reinterpret_cast<sockaddr*>(&sender), &sender_length);
  if (bytes < 0) {
    if (errno == EINTR || errno == EAGAIN) return std::nullopt;
    throw InputError(name(), "recv", std::strerror(errno));
  }
  UdpDatagram datagram;
  datagram.payload = std::span<const std::uint8_t>(buffer_.data(), static_cast<std::size_t>(bytes));
  datagram.capture_time_s = now_utc_s();
  datagram.src_address = ntohl(sender.sin_addr.s_addr);
  datagram.src_port = ntohs(sender.sin_port);
  datagram.dst_port = port;
  datagram.record = ++counts_.records;
  counts_.udp_datagrams = counts_.records;
  return datagram;
}

std::optional<UdpDatagram> UdpReceiver::next() {
  double waited_s = 0.0;
  while (!stopped_.load()) {
    pollfd descriptors[2] = {{socket_, POLLIN, 0}, {position_socket_, POLLIN, 0}};
    const nfds_t count = position_socket_ >= 0 ? 2 : 1;
    const int ready = ::poll(descriptors, count, kPollIntervalMs);
    if (ready < 0 && errno != EINTR) throw InputError(name(), "poll", std::strerror(errno));
    if (ready <= 0) {
      waited_s += kPollIntervalMs * 1e-3;
      if (idle_timeout_s_ > 0 && waited_s >= idle_timeout_s_) return std::nullopt;
      continue;
    }
    // Position packets first: at 1 Hz they never starve the data socket.
    if (count == 2 && (descriptors[1].revents & POLLIN)) {
      if (auto datagram = receive(position_socket_, *position_port_)) return datagram;
    }
    if (descriptors[0].revents & POLLIN) {
      if (auto datagram = receive(socket_, port_)) return datagram;
    }
  }
  return std::nullopt;
}

}  // namespace conicloc::io
