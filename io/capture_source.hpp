#pragma once
// A recorded capture of sensor packets, whatever its format (pcap/pcapng, MCAP, ROS 1 bag, ROS 2
// .db3): a DatagramSource that also counts what it read and what it had to skip. Open one with
// open_capture() (io/open_capture.hpp), which recognises the format by content.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/datagram_source.hpp"

namespace conicloc::io {

struct CaptureCounts {
  bool bag = false;                    ///< a bag: records count the messages of its topic
  std::size_t records = 0;             ///< records (pcap) or messages (bags) read, complete ones
  std::size_t udp_datagrams = 0;       ///< delivered by next()
  std::size_t truncated_records = 0;   ///< the file ended (or broke) inside a record
  std::size_t snap_length_cut = 0;     ///< captured fewer bytes than the frame had
  std::size_t not_ipv4_udp = 0;        ///< ARP, IPv6, TCP, ICMP, IP fragments, other link payloads
  std::size_t malformed = 0;           ///< UDP length beyond the captured bytes, bad IHL
  std::size_t foreign_port = 0;        ///< UDP to a port not asked for
  std::size_t ip_length_mismatch = 0;  ///< kept: IPv4 total length disagrees, UDP datagram whole
  std::size_t bad_chunks = 0;          ///< bags: chunks that did not decompress (skipped)
  std::size_t bad_messages = 0;        ///< bags: messages that did not decode (skipped)
  /// Bags: the first kNamedProblems skipped chunks and messages, each naming its place.
  std::vector<std::string> problems;
  static constexpr std::size_t kNamedProblems = 20;
  std::string stop_message;  ///< why reading stopped early (a broken record)
  /// Byte offset of the record where reading stopped (nullopt where the format gives none).
  std::optional<std::uint64_t> stop_offset;
};

class CaptureSource : public DatagramSource {
 public:
  virtual const CaptureCounts& counts() const = 0;
  /// "pcap", "pcapng", "MCAP", "ROS 1 bag", "ROS 2 db3".
  virtual std::string format() const = 0;
};

}  // namespace conicloc::io
