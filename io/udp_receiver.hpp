#pragma once
// Live UDP input: binds a datagram socket on a port (any local address, no root needed for ports
// above 1023) and returns the sensor's packets as they arrive.
//
// Example:
//   io::UdpReceiver receiver(2368);                      // throws InputError if the port is taken
//   while (auto datagram = receiver.next()) { ... }      // nullopt after `idle_timeout_s` silence
//   receiver.stop();                                     // from another thread / a signal handler

#include <atomic>
#include <cstdint>
#include <vector>

#include "io/datagram_source.hpp"

namespace conicloc::io {

class UdpReceiver : public DatagramSource {
 public:
  /// `idle_timeout_s` ≤ 0: wait forever (until stop()).
  explicit UdpReceiver(std::uint16_t port, double idle_timeout_s = 0.0);
  ~UdpReceiver() override;
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;

  std::optional<UdpDatagram> next() override;
  std::string name() const override;

  /// Makes next() return nullopt within ~0.2 s. Safe to call from a signal handler.
  void stop() { stopped_.store(true); }
  /// The port actually bound (useful when constructed with port 0).
  std::uint16_t port() const { return port_; }

 private:
  int socket_ = -1;
  std::uint16_t port_ = 0;
  double idle_timeout_s_ = 0.0;
  std::atomic<bool> stopped_{false};
  std::vector<std::uint8_t> buffer_;
  std::size_t count_ = 0;
};

}  // namespace conicloc::io
