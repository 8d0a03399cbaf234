#pragma once
// Live UDP input: binds a datagram socket on a port (any local address or one given, no root
// needed for ports above 1023) and returns the sensor's packets as they arrive. A second socket
// on the position port (a Velodyne sends its position packets to 8308, its data to 2368) is read
// alongside when asked for; its datagrams carry that port as dst_port, as in a capture.
//
// Example:
//   io::UdpReceiver receiver({.listen = {"", 2368}, .position_port = 8308, .idle_timeout_s = 5});
//   while (auto datagram = receiver.next()) { ... }      // nullopt after `idle_timeout_s` silence
//   receiver.stop();                                     // from another thread / a signal handler

#include <atomic>
#include <cstdint>
#include <optional>
#include <vector>

#include "io/capture_source.hpp"
#include "io/udp_endpoint.hpp"

namespace conicloc::io {

struct UdpReceiverConfig {
  UdpEndpoint listen;                          ///< port 0: any free port (see port())
  std::optional<std::uint16_t> position_port;  ///< also listen here (same address); 0: any free
  double idle_timeout_s = 0.0;                 ///< ≤ 0: wait forever (until stop())
};

class UdpReceiver : public CaptureSource {
 public:
  /// Throws InputError (naming the address) when a socket cannot be bound.
  explicit UdpReceiver(const UdpReceiverConfig& config);
  /// Data port only, on every local address.
  explicit UdpReceiver(std::uint16_t port, double idle_timeout_s = 0.0);
  ~UdpReceiver() override;
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;

  /// The next datagram of either socket; `record` numbers them in arrival order.
  std::optional<UdpDatagram> next() override;
  /// "udp://ADDR:PORT" (ADDR empty for every local address).
  std::string name() const override;
  /// records = udp_datagrams = datagrams received. Read it from the thread calling next().
  const CaptureCounts& counts() const override { return counts_; }
  std::string format() const override { return "live UDP"; }

  /// Makes next() return nullopt within ~0.2 s. Safe to call from a signal handler.
  void stop() { stopped_.store(true); }
  /// The port actually bound (useful when constructed with port 0).
  std::uint16_t port() const { return port_; }
  /// The position port actually bound; nullopt when not listening for position packets.
  std::optional<std::uint16_t> position_port() const { return position_port_; }

 private:
  int bind_socket(std::uint16_t port, std::uint16_t& bound_port) const;
  /// Reads one datagram from `socket` into buffer_.
  std::optional<UdpDatagram> receive(int socket, std::uint16_t port);

  std::string host_;
  int socket_ = -1;
  int position_socket_ = -1;
  std::uint16_t port_ = 0;
  std::optional<std::uint16_t> position_port_;
  double idle_timeout_s_ = 0.0;
  std::atomic<bool> stopped_{false};
  std::vector<std::uint8_t> buffer_;
  CaptureCounts counts_;
};

}  // namespace conicloc::io
