#pragma once
// Where UDP payloads come from: a capture file (PcapReader) or a live socket (UdpReceiver). The
// Velodyne stream reads either through this interface.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace conicloc::io {

struct UdpDatagram {
  std::span<const std::uint8_t> payload;  ///< valid until the next call to next()
  double capture_time_s = 0.0;            ///< capture / arrival time (UTC seconds)
  std::uint32_t src_address = 0;          ///< IPv4 sender, host byte order; 0 where unknown (bags)
  std::uint16_t src_port = 0;
  std::uint16_t dst_port = 0;
  std::size_t record = 0;  ///< 1-based record (or datagram) number, for messages
};

class DatagramSource {
 public:
  virtual ~DatagramSource() = default;
  /// The next datagram, or nullopt at the end of the input.
  virtual std::optional<UdpDatagram> next() = 0;
  /// A name for messages (file path or "udp://:2368").
  virtual std::string name() const = 0;
};

}  // namespace conicloc::io
