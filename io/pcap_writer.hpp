#pragma once
// Writes classic pcap captures (magic a1b2c3d4, microsecond timestamps, LINKTYPE_ETHERNET) of
// Ethernet / IPv4 / UDP frames, as Wireshark or tcpdump would record a Velodyne sensor: by default
// 192.168.1.201:2368 → 255.255.255.255:2368 from a Velodyne MAC to broadcast. IPv4 header and UDP
// checksums and all lengths are filled in. Readable by io::PcapReader, tcpdump, Wireshark,
// VeloView.
//
// Example:
//   io::PcapWriter pcap("run.pcap");                        // throws InputError if not writable
//   pcap.write_udp(packet.payload, 1.7e9 + packet.time_s);   // capture time: UTC seconds
//   pcap.write_udp(position_payload, t_utc, {.src_port = 8308, .dst_port = 8308});
//   pcap.close();                                            // or let the destructor do it

#include <array>
#include <cstdint>
#include <fstream>
#include <span>
#include <string>
#include <vector>

namespace conicloc::io {

struct UdpEndpoints {
  std::array<std::uint8_t, 6> src_mac{0x60, 0x76, 0x88, 0x00, 0x00, 0x01};  // Velodyne OUI
  std::array<std::uint8_t, 6> dst_mac{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  std::array<std::uint8_t, 4> src_ip{192, 168, 1, 201};
  std::array<std::uint8_t, 4> dst_ip{255, 255, 255, 255};
  std::uint16_t src_port = 2368;
  std::uint16_t dst_port = 2368;
};

/// An Ethernet II frame carrying `payload` in IPv4/UDP, checksums computed. `ip_id` is the IPv4
/// identification field.
std::vector<std::uint8_t> make_udp_frame(std::span<const std::uint8_t> payload,
                                         const UdpEndpoints& endpoints, std::uint16_t ip_id = 0);

/// RFC 1071 one's-complement sum folded to 16 bits (not yet inverted) over `bytes`, starting at
/// `sum`.
std::uint32_t ones_complement_sum(std::span<const std::uint8_t> bytes, std::uint32_t sum = 0);

class PcapWriter {
 public:
  /// Creates (truncates) `path` and writes the global header. Throws InputError on failure.
  explicit PcapWriter(const std::string& path);
  ~PcapWriter();
  PcapWriter(const PcapWriter&) = delete;
  PcapWriter& operator=(const PcapWriter&) = delete;

  /// Writes one UDP datagram as an Ethernet frame stamped `utc_time_s` (rounded to 1 µs).
  void write_udp(std::span<const std::uint8_t> payload, double utc_time_s,
                 const UdpEndpoints& endpoints = {});

  /// Writes an arbitrary Ethernet frame (for tests of readers: bad frames, foreign protocols).
  void write_frame(std::span<const std::uint8_t> frame, double utc_time_s);

  /// Flushes and closes; throws InputError if the data did not reach the file.
  void close();

  std::size_t packets_written() const { return packets_; }

 private:
  std::string path_;
  std::ofstream out_;
  std::size_t packets_ = 0;
};

}  // namespace conicloc::io
